#include "io/colmap_database.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <sqlite3.h>

#include "aief/error.hpp"
#include "io/hdf5_file.hpp"
#include "io/json_writer.hpp"
#include "io/match_record.hpp"
#include "io/pairs_file.hpp"
#include "io/temporary_files.hpp"
#include "io/utf8.hpp"

namespace aief::io {

namespace {

// COLMAP 3.x's tables (colmap/src/base/database.cc), created as COLMAP creates them.
constexpr const char* kSchema = R"sql(
CREATE TABLE cameras (camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, model INTEGER NOT NULL,
  width INTEGER NOT NULL, height INTEGER NOT NULL, params BLOB, prior_focal_length INTEGER NOT NULL);
CREATE TABLE images (image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, name TEXT NOT NULL UNIQUE,
  camera_id INTEGER NOT NULL, prior_qw REAL, prior_qx REAL, prior_qy REAL, prior_qz REAL, prior_tx REAL,
  prior_ty REAL, prior_tz REAL, CONSTRAINT image_id_check CHECK(image_id >= 0 and image_id < 2147483647),
  FOREIGN KEY(camera_id) REFERENCES cameras(camera_id));
CREATE UNIQUE INDEX index_name ON images(name);
CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols INTEGER NOT NULL,
  data BLOB, FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols INTEGER NOT NULL,
  data BLOB, FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE matches (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB);
CREATE TABLE two_view_geometries (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL,
  cols INTEGER NOT NULL, data BLOB, config INTEGER NOT NULL, F BLOB, E BLOB, H BLOB, qvec BLOB, tvec BLOB);
)sql";

constexpr int kSimpleRadial = 2;               // COLMAP's camera model id
constexpr long long kMaxImageId = 2147483647;  // pair_id = id1 * kMaxImageId + id2 (COLMAP)
constexpr double kFocalGuess = 1.2;            // COLMAP's focal prior without EXIF, times max(w, h)
constexpr float kColmapOrigin = 0.5f;          // pixel centre in COLMAP's corner-origin pixels

class Database {
 public:
  explicit Database(const std::string& path) : path_(path) {
    if (sqlite3_open(path.c_str(), &db_) != SQLITE_OK) fail("cannot create");
  }
  ~Database() { sqlite3_close(db_); }
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  void exec(const char* sql) {
    if (sqlite3_exec(db_, sql, nullptr, nullptr, nullptr) != SQLITE_OK) fail("cannot run SQL");
  }
  [[noreturn]] void fail(const std::string& what) {
    throw Error(what + " in COLMAP database '" + path_ + "': " + sqlite3_errmsg(db_));
  }
  sqlite3* get() { return db_; }

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

// An insert prepared once and run once a row: preparing it costs about 20k instructions, as much
// as the insert itself.
class Insert {
 public:
  Insert(Database& db, const char* sql) : db_(db) {
    if (sqlite3_prepare_v2(db.get(), sql, -1, &statement_, nullptr) != SQLITE_OK)
      db.fail("cannot prepare");
  }
  ~Insert() { sqlite3_finalize(statement_); }
  Insert(const Insert&) = delete;
  Insert& operator=(const Insert&) = delete;

  // Binds the row's values with `bind` and inserts it.
  template <class Bind>
  void run(Bind&& bind) {
    bind(statement_);
    if (sqlite3_step(statement_) != SQLITE_DONE) db_.fail("cannot insert");
    sqlite3_reset(statement_);
  }

 private:
  Database& db_;
  sqlite3_stmt* statement_ = nullptr;
};

template <class T>
void bind_blob(sqlite3_stmt* statement, int column, const std::vector<T>& values) {
  sqlite3_bind_blob(statement, column, values.data(), static_cast<int>(values.size() * sizeof(T)),
                    SQLITE_TRANSIENT);
}

void write_database(Database& db, const Hdf5File& features, const Hdf5File& matches_file,
                    const PairsList& pairs, ColmapExport& summary) {
  db.exec(kSchema);
  db.exec("BEGIN TRANSACTION");
  Insert insert_camera(db, "INSERT INTO cameras VALUES (?, ?, ?, ?, ?, 0)"),
      insert_image(db, "INSERT INTO images (image_id, name, camera_id) VALUES (?, ?, ?)"),
      insert_keypoints(db, "INSERT INTO keypoints VALUES (?, ?, 2, ?)"),
      insert_descriptors(db, "INSERT INTO descriptors VALUES (?, ?, 32, ?)"),
      insert_matches(db, "INSERT INTO matches VALUES (?, ?, 2, ?)");
  using Images = std::unordered_map<std::string, std::pair<long long, int>>;
  Images images;           // name -> (image id, keypoints)
  std::string first_name;  // COLMAP matches every image's descriptors with every other's
  DescriptorKind first_descriptor = DescriptorKind::rbrief;
  for (const std::string& name : features.feature_names()) {
    const Features f = features.read_features(name);
    if (images.empty()) {
      first_name = name;
      first_descriptor = f.descriptor;
    }
    require_same_descriptor(first_descriptor, "'" + first_name + "'", f.descriptor,
                            "'" + name + "' (both in '" + features.path() + "')");
    const long long id = static_cast<long long>(images.size()) + 1;
    images[name] = {id, static_cast<int>(f.keypoints.size())};
    if (!is_valid_utf8(name)) summary.names_not_utf8.push_back(name);
    const std::vector<double> params = {kFocalGuess * std::max(f.image_width, f.image_height),
                                        f.image_width / 2.0, f.image_height / 2.0, 0.0};
    insert_camera.run([&](sqlite3_stmt* s) {
      sqlite3_bind_int64(s, 1, id);
      sqlite3_bind_int(s, 2, kSimpleRadial);
      sqlite3_bind_int(s, 3, f.image_width);
      sqlite3_bind_int(s, 4, f.image_height);
      bind_blob(s, 5, params);
    });
    insert_image.run([&](sqlite3_stmt* s) {
      sqlite3_bind_int64(s, 1, id);
      sqlite3_bind_text(s, 2, name.data(), static_cast<int>(name.size()),
                        SQLITE_TRANSIENT);  // the bytes, as COLMAP
      sqlite3_bind_int64(s, 3, id);
    });
    std::vector<float> xy;
    std::vector<std::uint8_t> descriptors;
    for (std::size_t i = 0; i < f.keypoints.size(); ++i) {
      xy.push_back(f.keypoints[i].x + kColmapOrigin);
      xy.push_back(f.keypoints[i].y + kColmapOrigin);
      descriptors.insert(descriptors.end(), f.descriptors[i].begin(), f.descriptors[i].end());
    }
    const auto rows = static_cast<int>(f.keypoints.size());
    insert_keypoints.run([&](sqlite3_stmt* s) {
      sqlite3_bind_int64(s, 1, id);
      sqlite3_bind_int(s, 2, rows);
      bind_blob(s, 3, xy);
    });
    insert_descriptors.run([&](sqlite3_stmt* s) {
      sqlite3_bind_int64(s, 1, id);
      sqlite3_bind_int(s, 2, rows);
      bind_blob(s, 3, descriptors);
    });
    ++summary.images;
  }
  // Each name of the pairs list looked up once, not twice a pair.
  std::vector<Images::const_iterator> image_of_name;
  image_of_name.reserve(pairs.names.size());
  for (const std::string& name : pairs.names) image_of_name.push_back(images.find(name));
  std::unordered_set<long long> written;
  PairRecords records(features, MatchOptions{});  // each image's features as the file has them
  std::vector<std::string> stale;                 // pairs matched from other features
  for (std::size_t pair = 0; pair < pairs.size(); ++pair) {
    const std::string &name0 = pairs.name0(pair), &name1 = pairs.name1(pair);
    const auto a = image_of_name[pairs.pairs[pair].first],
               b = image_of_name[pairs.pairs[pair].second];
    if (a == images.end() || b == images.end())
      throw Error("pair '" + name0 + " " + name1 + "': image '" +
                  (a == images.end() ? name0 : name1) + "' is not in '" + features.path() + "'");
    std::size_t queries = 0;
    std::optional<std::vector<Match>> found = matches_file.find_matches(name0, name1, &queries);
    const bool swapped = !found;
    if (swapped) found = matches_file.find_matches(name1, name0, &queries);
    if (!found)
      throw Error("pair '" + name0 + " " + name1 + "' has no matches in '" + matches_file.path() +
                  "'");
    const std::vector<Match>& matches = *found;
    // Matches of features the features file no longer holds (re-extracted since, with other
    // options or from a changed image): refused, as match --pairs redoes them on a rerun.
    if (const std::optional<PairRecord> recorded = swapped
                                                       ? matches_file.pair_record(name1, name0)
                                                       : matches_file.pair_record(name0, name1)) {
      PairRecord now = swapped ? records.of(name1, name0) : records.of(name0, name1);
      now.matcher = recorded->matcher;  // only the features matter here
      const std::vector<std::string> changes = swapped ? pair_changes(recorded, now, name1, name0)
                                                       : pair_changes(recorded, now, name0, name1);
      if (!changes.empty()) {  // the pair and its first change, shortened to its first option
        std::string why = changes.front();
        if (const std::size_t more = why.find(", ", why.find(": ")); more != std::string::npos)
          why = why.substr(0, more) + ", ...";
        stale.push_back("'" + name0 + " " + name1 + "': " + why);
        continue;
      }
    }
    const auto& query = swapped ? b : a;  // the image whose keypoints the matches' queries index
    const auto& train = swapped ? a : b;
    // matches0 has a row per keypoint of image 0: another length means other features.
    if (queries != static_cast<std::size_t>(query->second.second))
      throw Error("pair '" + name0 + " " + name1 + "': matches0 has " + std::to_string(queries) +
                  " rows but '" + query->first + "' has " + std::to_string(query->second.second) +
                  " keypoints in '" + features.path() +
                  "' (features and matches from different runs?)");
    for (const Match& m : matches)
      if (m.query < 0 || m.query >= query->second.second || m.train < 0 ||
          m.train >= train->second.second) {
        const bool bad_query = m.query < 0 || m.query >= query->second.second;
        const auto& image = bad_query ? query : train;
        throw Error("pair '" + name0 + " " + name1 + "': a match names keypoint " +
                    std::to_string(bad_query ? m.query : m.train) + " of '" + image->first +
                    "', which has " + std::to_string(image->second.second) + " in '" +
                    features.path() + "' (features and matches from different runs?)");
      }
    long long id0 = query->second.first, id1 = train->second.first;  // id0: the queries' image
    const bool flip = id0 > id1;  // COLMAP keys a pair by (smaller id, larger id)
    const long long pair_id = std::min(id0, id1) * kMaxImageId + std::max(id0, id1);
    if (!written.insert(pair_id).second) continue;  // listed twice, or both ways
    std::vector<std::uint32_t> rows;
    for (const Match& m : matches) {
      rows.push_back(static_cast<std::uint32_t>(flip ? m.train : m.query));
      rows.push_back(static_cast<std::uint32_t>(flip ? m.query : m.train));
    }
    insert_matches.run([&](sqlite3_stmt* s) {
      sqlite3_bind_int64(s, 1, pair_id);
      sqlite3_bind_int(s, 2, static_cast<int>(matches.size()));
      bind_blob(s, 3, rows);
    });
    ++summary.pairs;
    summary.matches += static_cast<long long>(matches.size());
  }
  if (!stale.empty()) {
    constexpr std::size_t kNamed = 3;
    std::string named;
    for (std::size_t i = 0; i < stale.size() && i < kNamed; ++i)
      named += (i > 0 ? "; " : "") + stale[i];
    if (stale.size() > kNamed) named += "; and " + std::to_string(stale.size() - kNamed) + " more";
    throw Error(std::to_string(stale.size()) + " pair(s) of '" + matches_file.path() +
                "' were matched from other features than '" + features.path() +
                "' holds now (pair " + named +
                "): run aief match --pairs again with these "
                "features (it matches those pairs again); no database was written");
  }
  db.exec("COMMIT");
}

}  // namespace

ColmapExport export_colmap_database(const std::string& database, const std::string& features_h5,
                                    const std::string& matches_h5, const std::string& pairs_txt) {
  std::error_code ec;
  if (std::filesystem::exists(database, ec))
    throw Error("COLMAP database '" + database + "' exists already (remove it first)");
  const Hdf5File features(features_h5, Hdf5File::Mode::read);
  const Hdf5File matches(matches_h5, Hdf5File::Mode::read);
  PairsList pairs = read_pairs(pairs_txt);
  // Written to a locked temporary of this export's own, then renamed to `database` unless
  // another export created it meanwhile: a killed or failed export leaves no database.
  remove_stale_temporaries_of(database);
  LockedTemporary temporary(database);
  const std::string journal = temporary.path() + "-journal";
  ColmapExport summary;
  summary.notes = std::move(pairs.notes);
  try {
    Database db(temporary.path());
    write_database(db, features, matches, pairs, summary);
  } catch (...) {
    std::filesystem::remove(journal, ec);
    throw;
  }
  std::filesystem::remove(journal, ec);
  if (!temporary.rename_unless_output_exists())
    throw Error("COLMAP database '" + database +
                "' was created by another run meanwhile (remove it first)");
  return summary;
}

}  // namespace aief::io
