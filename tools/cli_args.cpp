#include "tools/cli_args.hpp"

#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

#include <tbb/info.h>

#include "aief/error.hpp"

namespace aief::cli {

Args::Args(const std::vector<std::string>& tokens, const std::vector<FlagSpec>& spec) {
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string& token = tokens[i];
    if (token.size() < 2 || token[0] != '-' || (std::isdigit(static_cast<unsigned char>(token[1])) != 0)) {
      positionals_.push_back(token);
      continue;
    }
    std::string name = token, inline_value;
    bool has_inline = false;
    if (const std::size_t eq = token.find('='); eq != std::string::npos && token.rfind("--", 0) == 0) {
      name = token.substr(0, eq);
      inline_value = token.substr(eq + 1);
      has_inline = true;
    }
    const FlagSpec* match = nullptr;
    for (const FlagSpec& flag : spec)
      if (flag.name == name || (!flag.alias.empty() && flag.alias == name)) match = &flag;
    if (!match) throw UsageError("unknown option " + name);
    if (!match->takes_value) {
      if (has_inline) throw UsageError(match->name + " takes no value");
      values_.emplace_back(match->name, "");
      continue;
    }
    if (has_inline) {
      values_.emplace_back(match->name, inline_value);
    } else {
      if (i + 1 >= tokens.size()) throw UsageError(match->name + " expects a value");
      values_.emplace_back(match->name, tokens[++i]);
    }
  }
}

bool Args::has(const std::string& name) const {
  for (const auto& [flag, value] : values_)
    if (flag == name) return true;
  return false;
}

std::optional<std::string> Args::get(const std::string& name) const {
  std::optional<std::string> result;
  for (const auto& [flag, value] : values_)
    if (flag == name) result = value;  // the last one wins
  return result;
}

int Args::get_int(const std::string& name, int fallback, int min, int max) const {
  const std::optional<std::string> text = get(name);
  if (!text) return fallback;
  std::size_t used = 0;
  long long value = 0;
  try {
    value = std::stoll(*text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text->size() || value < min || value > max)
    throw UsageError(name + " expects an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "], got '" +
                     *text + "'");
  return static_cast<int>(value);
}

double Args::get_double(const std::string& name, double fallback, double min, double max, bool min_is_exclusive) const {
  const std::optional<std::string> text = get(name);
  if (!text) return fallback;
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(*text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  const bool below = min_is_exclusive ? value <= min : value < min;
  if (used == 0 || used != text->size() || !std::isfinite(value) || below || value > max) {
    std::ostringstream message;
    message << name << " expects a number in " << (min_is_exclusive ? "(" : "[") << min << ", " << max << "], got '" << *text
            << "'";
    throw UsageError(message.str());
  }
  return value;
}

namespace {

bool parse_on_off(const std::string& flag, const std::string& text) {
  if (text == "on") return true;
  if (text == "off") return false;
  throw UsageError(flag + " expects on or off, got '" + text + "'");
}

}  // namespace

std::vector<FlagSpec> extractor_flags() {
  return {{"--mode", "", true},          {"--features", "", true},      {"--levels", "", true},
          {"--scale", "", true},         {"--block", "", true},         {"--threshold", "", true},
          {"--entropy", "", true},       {"--fast-threshold", "", true}, {"--fast-min-threshold", "", true},
          {"--kernels", "", true},       {"--threads", "", true},       {"--pool", "", true},
          {"--coordinates", "", true},   {"--subpixel", "", true},      {"--starvation-guard", "", true},
          {"--auto-uniform-blocks", "", true}, {"--ranking", "", true},       {"--auto-two-classes", "", true}};
}

ExtractorOptions extractor_options(const Args& args) {
  const ExtractorOptions defaults;
  ExtractorOptions options;
  // Ranges here only catch typos early; ExtractorOptions::validate() is the authority.
  options.n_features = args.get_int("--features", defaults.n_features, 1, 1'000'000);
  options.n_levels = args.get_int("--levels", defaults.n_levels, 1, 32);
  options.scale_factor = args.get_double("--scale", defaults.scale_factor, 1.0, 4.0, /*min_is_exclusive=*/true);
  options.block_size = args.get_int("--block", defaults.block_size, 8, 1024);
  options.fast_threshold = args.get_int("--fast-threshold", defaults.fast_threshold, 1, 254);
  options.fast_min_threshold = args.get_int("--fast-min-threshold", defaults.fast_min_threshold, 1, 254);
  options.threads = args.get_int("--threads", defaults.threads, 0, 256);
  // More threads than the machine runs gains nothing (output never depends on the count) and
  // makes TBB print its own warning: use what there is, and say so.
  if (const int available = tbb::info::default_concurrency(); options.threads > available) {
    std::cerr << "aief: note: --threads " << options.threads << " is more than the " << available
              << " hardware threads this process may use; using " << available << "\n";
    options.threads = available;
  }
  // A mode sets the distribution and the default entropy measure; a flag the user gave either
  // takes effect over it or, when the mode cannot honour it, is refused naming the conflict.
  const std::optional<std::string> entropy_flag = args.get("--entropy"), threshold_flag = args.get("--threshold");
  Mode mode = Mode::aief;
  try {
    if (const auto kernels = args.get("--kernels")) options.kernels = parse_kernel_set(*kernels);
    if (const auto name = args.get("--mode")) mode = parse_mode(*name);
    options = options_for_mode(mode, options);
    if (entropy_flag) options.entropy = parse_entropy_measure(*entropy_flag);
    // The quality options refine the mode (docs/design.md §11), so they apply after it.
    if (const auto pool = args.get("--pool")) options.candidate_pool = parse_candidate_pool(*pool);
    if (const auto map = args.get("--coordinates")) options.coordinates = parse_coordinate_map(*map);
    if (const auto subpixel = args.get("--subpixel")) options.subpixel = parse_on_off("--subpixel", *subpixel);
    if (const auto guard = args.get("--starvation-guard")) options.starvation_guard = parse_starvation_guard(*guard);
    if (const auto uniform = args.get("--auto-uniform-blocks")) {
      if (*uniform != "skip" && *uniform != "count")
        throw UsageError("--auto-uniform-blocks expects skip or count, got '" + *uniform + "'");
      options.auto_skips_uniform_blocks = *uniform == "skip";
    }
    if (const auto ranking = args.get("--ranking")) options.candidate_ranking = parse_candidate_ranking(*ranking);
    if (const auto two = args.get("--auto-two-classes"))
      options.auto_requires_two_classes = parse_on_off("--auto-two-classes", *two);
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  if (mode == Mode::orbslam2 && options.entropy != EntropyMeasure::off)
    throw UsageError("--mode orbslam2 has no entropy mask, so --entropy " + *entropy_flag +
                     " cannot apply (a quadtree with an entropy mask is --mode quadtree-entropy)");
  if (options.entropy == EntropyMeasure::off && threshold_flag)
    throw UsageError(std::string("--threshold sets F of the entropy mask, which ") +
                     (entropy_flag ? "--entropy off" : "--mode orbslam2") + " turns off: drop one of the two");
  if (threshold_flag && *threshold_flag == "auto") {
    options.auto_threshold = true;
  } else {
    options.entropy_threshold = args.get_double("--threshold", defaults.entropy_threshold, 0.0, 64.0);
  }
  try {
    options.validate();
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  return options;
}

std::string extractor_flags_help() {
  const ExtractorOptions d;
  std::ostringstream out;
  out << "  --mode M              aief | aief-paper | orbslam2 | quadtree-entropy (default aief).\n"
      << "                        aief-paper is the published algorithm to the byte (x * scale, no\n"
      << "                        sub-pixel, no pool, frame-wide guard); orbslam2 keeps x * scale too\n"
      << "  --features N          keypoints wanted over all levels (default " << d.n_features << ")\n"
      << "  --levels L            pyramid levels (default " << d.n_levels << ")\n"
      << "  --scale S             scale factor between levels (default " << d.scale_factor << ")\n"
      << "  --block B             entropy / distribution block side, pixels (default " << d.block_size << ")\n"
      << "  --threshold F|auto    entropy threshold F in bits, or auto: Otsu split of the frame's own\n"
      << "                        block entropies (default " << d.entropy_threshold << ")\n"
      << "  --entropy E           histogram | intensity | off (default " << to_string(d.entropy) << "; off: no mask)\n"
      << "  --fast-threshold T    FAST threshold (default " << d.fast_threshold << ")\n"
      << "  --fast-min-threshold T  retry threshold for a block without corners (default " << d.fast_min_threshold << ")\n"
      << "  --kernels K           auto | scalar | sse4.2 | avx2 | avx512 | neon64 (default auto; same output)\n"
      << "  --threads T           worker threads, 0 = all cores (default " << d.threads << "; same output)\n"
      << "  --pool P|inf          candidate pool: each level keeps its best ceil(P x N_level) candidates\n"
      << "                        before the water-level distribution; inf = none (default " << d.candidate_pool << ")\n"
      << "  --coordinates C       pixel-centre: (x + 0.5) * W0 / Wn - 0.5 | scaled: x * scale^n (default "
      << to_string(d.coordinates) << ")\n"
      << "  --subpixel on|off     parabola peak of the FAST scores per axis (default " << (d.subpixel ? "on" : "off") << ")\n"
      << "  --starvation-guard G  level: F lowered per level until it has its budget, and what a level\n"
      << "                        still lacks goes to the levels with candidates to spare, finest first |\n"
      << "                        frame: F lowered for the whole frame until it has n_features (default "
      << to_string(d.starvation_guard) << ")\n"
      << "  --auto-uniform-blocks skip|count  whether one-gray-level blocks take part in the automatic F\n"
      << "                        (default " << (d.auto_skips_uniform_blocks ? "skip" : "count") << ")\n"
      << "  --ranking cross|peak  what the pool and the distribution rank candidates by: cross = FAST scores\n"
      << "                        summed over the corner and its 4 neighbours, peak = the corner's score\n"
      << "                        (default " << to_string(d.candidate_ranking) << ")\n"
      << "  --auto-two-classes on|off  automatic F: split only when the block entropies form two classes\n"
      << "                        (Otsu's effectiveness >= 0.75), else F = 0 keeps every block (default "
      << (d.auto_requires_two_classes ? "on" : "off") << ")\n"
      << "  (--pool, --coordinates, --subpixel, --starvation-guard, --auto-uniform-blocks, --ranking and\n"
      << "   --auto-two-classes apply after --mode)\n";
  return out.str();
}

}  // namespace aief::cli
