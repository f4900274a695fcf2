#include "tools/eval/report.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <thread>

#include "io/json_writer.hpp"
#include "io/plot.hpp"

namespace aief::eval {

namespace {

// The paper's figures (docs/design.md §14), by method and sequence; absent where it has none.
struct PaperFigures {
  std::map<std::string, double> cmr_percent, time_s;
};

const std::map<Method, PaperFigures>& paper_figures() {
  static const std::map<Method, PaperFigures> figures = {
      {Method::orbslam2,
       {{{"graf", 86.86}, {"leuven", 91.81}, {"boat", 83.46}, {"bikes", 87.93}},
        {{"graf", 0.0370}, {"leuven", 0.0381}, {"boat", 0.0572}, {"bikes", 0.0422}}}},
      {Method::quadtree_entropy,
       {{{"graf", 86.86}, {"leuven", 92.38}, {"boat", 83.46}, {"bikes", 87.93}},
        {{"graf", 0.0609}, {"leuven", 0.0531}, {"boat", 0.2538}, {"bikes", 0.0619}}}},
      {Method::aief_paper_adaptive,
       {{{"graf", 89.07}, {"leuven", 93.18}, {"boat", 87.50}, {"bikes", 91.32}},
        {{"graf", 0.0331}, {"leuven", 0.0293}, {"boat", 0.0380}, {"bikes", 0.0331}}}},
      {Method::opencv_sift,
       {{{"graf", 82.26}, {"leuven", 85.08}, {"boat", 77.37}, {"bikes", 63.85}},
        {{"graf", 0.2458}, {"leuven", 0.2508}, {"boat", 0.3603}, {"bikes", 0.3377}}}},
  };
  return figures;
}

std::string fmt(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

int find_pair(const EvalRun& run, const std::string& sequence, int target) {
  for (std::size_t i = 0; i < run.pairs.size(); ++i)
    if (run.pairs[i].sequence == sequence && run.pairs[i].target == target)
      return static_cast<int>(i);
  return -1;
}

std::vector<std::string> sequences_of(const EvalRun& run) {
  std::vector<std::string> out;
  for (const PairInput& p : run.pairs)
    if (std::find(out.begin(), out.end(), p.sequence) == out.end()) out.push_back(p.sequence);
  return out;
}

// One of the paper's tables over img1 -> img2 of graf, leuven, boat, bikes.
template <class Cell>
void paper_table(std::ostringstream& md, const EvalRun& run, const std::string& title,
                 const std::string& note, Cell cell) {
  md << "### " << title << "\n\n" << note << "\n\n| method |";
  for (const std::string& s : kPaperSequences) md << ' ' << s << " |";
  md << "\n|---|";
  for (std::size_t i = 0; i < kPaperSequences.size(); ++i) md << "---|";
  md << '\n';
  for (std::size_t m = 0; m < run.methods.size(); ++m) {
    md << "| " << method_name(run.methods[m]) << " |";
    for (const std::string& s : kPaperSequences) {
      const int p = find_pair(run, s, 2);
      md << ' '
         << (p < 0 ? std::string("n/a")
                   : cell(run.results[static_cast<std::size_t>(p)][m], run.methods[m], s))
         << " |";
    }
    md << '\n';
  }
  md << '\n';
}

std::string with_paper(const std::string& ours, const std::map<std::string, double>* paper,
                       const std::string& sequence, const char* format, double scale) {
  if (!paper || !paper->count(sequence)) return ours;
  return ours + " (paper " + fmt(format, paper->at(sequence) * scale) + ")";
}

// How Table 2 was timed, and how busy the machine was meanwhile.
std::string timing_note(const EvalRun& run) {
  std::string note =
      "One image, one thread, CPU time of the process: the median of " +
      std::to_string(run.timing_rounds) +
      " interleaved rounds (every method once per round, the order rotated by one each round), "
      "[fastest, slowest] round in brackets; evaluation.json also has the wall-clock medians "
      "(extract_wall_ms), which on a busy machine include waiting for a core. The paper's figures "
      "are seconds on its laptop, shown here in ms.";
  if (run.load.highest >= 0)
    note += " Machine load while timing: 1-minute load average " + fmt("%.1f", run.load.lowest) +
            " to " + fmt("%.1f", run.load.highest) + " on " +
            std::to_string(std::thread::hardware_concurrency()) + " hardware threads" +
            (run.load.highest > std::thread::hardware_concurrency() * 0.5
                 ? " (a busy machine: compare the rows with each other, not with other runs)."
                 : ".");
  return note;
}

int method_index(const EvalRun& run, Method method) {
  for (std::size_t m = 0; m < run.methods.size(); ++m)
    if (run.methods[m] == method) return static_cast<int>(m);
  return -1;
}

// One method's figures over every pair of the run.
struct MethodSummary {
  int correct_2_to_4 = 0;
  double accuracy = 0, h1 = 0, h3 = 0, h5 = 0, repeatability = 0, spread = 0, time_ms = 0;
};

MethodSummary summarize(const EvalRun& run, std::size_t m) {
  MethodSummary sum;
  const double n = static_cast<double>(run.pairs.size());
  if (run.pairs.empty()) return sum;
  for (std::size_t p = 0; p < run.pairs.size(); ++p) {
    const PairResult& r = run.results[p][m];
    if (run.pairs[p].target <= 4) sum.correct_2_to_4 += r.correct;
    const bool has_model = r.corner_error >= 0;
    sum.accuracy += r.accuracy / n;
    sum.h1 += has_model && r.corner_error < 1.0 ? 1.0 / n : 0.0;
    sum.h3 += has_model && r.corner_error < 3.0 ? 1.0 / n : 0.0;
    sum.h5 += has_model && r.corner_error < 5.0 ? 1.0 / n : 0.0;
    sum.repeatability += r.repeatability / n;
    sum.spread += r.spread / n;
    sum.time_ms += r.extract_ms / n;
  }
  return sum;
}

}  // namespace

std::string hand_written_section(const std::string& previous_report) {
  const std::size_t at = previous_report.find(kHandWrittenMarker);
  return at == std::string::npos ? std::string() : previous_report.substr(at);
}

std::string markdown_report(const EvalRun& run, const std::string& plot_folder) {
  std::ostringstream md;
  md << "# aief evaluation on the Oxford affine sequences\n\n"
     << "Generated by `aief eval` in " << fmt("%.0f", run.seconds) << " s. Matcher: " << run.matcher
     << "; homography: our RANSAC (3 px, confidence 0.995, least-squares refit, inliers recounted);"
     << " times: extraction + description of img1, one thread, on this machine (the paper's: an "
        "i5-7200U)."
     << " 1000 features everywhere; OpenCV 4.6 baselines.\n\n";

  md << "## The paper's tables (img1 -> img2)\n\n";
  const auto figures = [](Method m) -> const PaperFigures* {
    const auto it = paper_figures().find(m);
    return it == paper_figures().end() ? nullptr : &it->second;
  };
  paper_table(md, run, "Table 1: correct matching rate CMR (%)",
              "CMR = RANSAC inliers / putative matches (Eq. 10).",
              [&](const PairResult& r, Method m, const std::string& s) {
                const PaperFigures* f = figures(m);
                return with_paper(fmt("%.2f", 100 * r.cmr), f ? &f->cmr_percent : nullptr, s,
                                  "%.2f", 1.0);
              });
  paper_table(md, run, "Table 2: extraction + description time (ms)", timing_note(run),
              [&](const PairResult& r, Method m, const std::string& s) {
                const PaperFigures* f = figures(m);
                const std::string ours = fmt("%.2f", r.extract_ms) + " [" +
                                         fmt("%.2f", r.extract_min_ms) + ", " +
                                         fmt("%.2f", r.extract_max_ms) + "]";
                return with_paper(ours, f ? &f->time_s : nullptr, s, "%.1f", 1000.0);
              });
  paper_table(
      md, run, "Table 3: putative matches (n)", "",
      [](const PairResult& r, Method, const std::string&) { return std::to_string(r.putative); });
  paper_table(
      md, run, "Table 4: RANSAC inliers (m)", "",
      [](const PairResult& r, Method, const std::string&) { return std::to_string(r.inliers); });

  const std::vector<std::string> sequences = sequences_of(run);
  md << "## Against the ground-truth homographies\n\n"
     << "Correct = putative matches within 3 px of where the true homography sends the point; "
        "accuracy = correct /"
     << " putative; homography success = mean corner error of our RANSAC model against the truth "
        "below 5 px.\n\n";
  md << "### Correct matches, sum over img1 -> img2..4\n\n| method |";
  for (const std::string& s : sequences) md << ' ' << s << " |";
  md << " total |\n|---|";
  for (std::size_t i = 0; i <= sequences.size(); ++i) md << "---|";
  md << '\n';
  const auto sum_correct = [&](std::size_t m, const std::string& s, int last) {
    int sum = 0;
    for (int t = 2; t <= last; ++t)
      if (const int p = find_pair(run, s, t); p >= 0)
        sum += run.results[static_cast<std::size_t>(p)][m].correct;
    return sum;
  };
  for (std::size_t m = 0; m < run.methods.size(); ++m) {
    md << "| " << method_name(run.methods[m]) << " |";
    int total = 0;
    for (const std::string& s : sequences) {
      const int c = sum_correct(m, s, 4);
      total += c;
      md << ' ' << c << " |";
    }
    md << ' ' << total << " |\n";
  }
  md << "\n### Summary over every pair\n\n"
     << "Correct: sum over img1 -> img2..4. Accuracy: mean over every pair. Homography accuracy as "
        "in HPatches: share of"
     << " pairs whose estimated homography has a mean corner error below 1, 3 and 5 px. "
        "Repeatability: keypoints of img1"
     << " found again in imgN within 3 px under the true homography, over the smaller visible "
        "count, mean over pairs."
     << " Spread: share of img1's 32 px cells holding a keypoint. Time: extraction + description "
        "of img1, CPU time, mean"
     << " of the per-pair medians (as in Table 2), ms.\n\n"
     << "| method | correct (2..4) | accuracy | H < 1 px | H < 3 px | H < 5 px | repeatability | "
        "spread | time ms |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t m = 0; m < run.methods.size(); ++m) {
    const MethodSummary sum = summarize(run, m);
    md << "| " << method_name(run.methods[m]) << " | " << sum.correct_2_to_4 << " | "
       << fmt("%.1f%%", 100 * sum.accuracy) << " | " << fmt("%.1f%%", 100 * sum.h1) << " | "
       << fmt("%.1f%%", 100 * sum.h3) << " | " << fmt("%.1f%%", 100 * sum.h5) << " | "
       << fmt("%.1f%%", 100 * sum.repeatability) << " | " << fmt("%.1f%%", 100 * sum.spread)
       << " | " << fmt("%.2f", sum.time_ms) << " |\n";
  }
  md << "\n### Per sequence over every pair: correct matches / mean accuracy / homography "
        "successes\n\n| method |";
  for (const std::string& s : sequences) md << ' ' << s << " |";
  md << "\n|---|";
  for (std::size_t i = 0; i < sequences.size(); ++i) md << "---|";
  md << '\n';
  for (std::size_t m = 0; m < run.methods.size(); ++m) {
    md << "| " << method_name(run.methods[m]) << " |";
    for (const std::string& s : sequences) {
      int correct = 0, ok = 0, n = 0;
      double accuracy = 0;
      for (std::size_t p = 0; p < run.pairs.size(); ++p) {
        if (run.pairs[p].sequence != s) continue;
        const PairResult& r = run.results[p][m];
        correct += r.correct;
        accuracy += r.accuracy;
        ok += r.homography_ok ? 1 : 0;
        ++n;
      }
      md << ' ' << correct << " / " << fmt("%.1f%%", n ? 100 * accuracy / n : 0.0) << " / " << ok
         << "/" << n << " |";
    }
    md << '\n';
  }

  // Adaptive thresholds chosen, and the automatic ones beside them.
  const int adaptive = method_index(run, Method::aief_adaptive),
            automatic = method_index(run, Method::aief_auto);
  if (adaptive >= 0 && automatic >= 0) {
    md << "\n### Entropy threshold F per pair: swept (adaptive) / pair-free automatic (image "
          "A)\n\n| pair | swept F | auto F |\n|---|---|---|\n";
    for (std::size_t p = 0; p < run.pairs.size(); ++p)
      md << "| " << run.pairs[p].sequence << " 1-" << run.pairs[p].target << " | "
         << fmt("%.1f", run.results[p][static_cast<std::size_t>(adaptive)].threshold) << " | "
         << fmt("%.2f", run.results[p][static_cast<std::size_t>(automatic)].threshold) << " |\n";
  }

  // The matching-quality targets, measured: both AIEF rows against cv::ORB.
  const int orb = method_index(run, Method::opencv_orb),
            paper = method_index(run, Method::aief_paper_adaptive);
  if (orb >= 0) {
    md << "\n## Quality targets (AIEF against OpenCV ORB 1000, 1.2, 8)\n\n";
    const MethodSummary o = summarize(run, static_cast<std::size_t>(orb));
    const auto verdict = [](bool met) { return met ? " (met)" : " (NOT met)"; };
    for (Method method : {Method::aief_auto, Method::aief_adaptive}) {
      const int m = method_index(run, method);
      if (m < 0) continue;
      const MethodSummary a = summarize(run, static_cast<std::size_t>(m));
      md << "- " << method_name(method) << ": correct matches (img1 -> img2..4) "
         << a.correct_2_to_4 << " vs " << o.correct_2_to_4
         << verdict(a.correct_2_to_4 > o.correct_2_to_4) << "; accuracy over all pairs "
         << fmt("%.2f%%", 100 * a.accuracy) << " vs " << fmt("%.2f%%", 100 * o.accuracy)
         << verdict(a.accuracy >= o.accuracy) << "; homography < 3 px " << fmt("%.1f%%", 100 * a.h3)
         << " vs " << fmt("%.1f%%", 100 * o.h3) << verdict(a.h3 >= o.h3) << "; spread "
         << fmt("%.1f%%", 100 * a.spread) << " vs " << fmt("%.1f%%", 100 * o.spread)
         << verdict(a.spread > o.spread);
      if (paper >= 0)
        md << "; time " << fmt("%.2f", a.time_ms) << " ms vs AIEF paper "
           << fmt("%.2f", summarize(run, static_cast<std::size_t>(paper)).time_ms) << " ms";
      md << ".\n";
    }
  }
  if (adaptive >= 0 && automatic >= 0) {
    double ratio_sum = 0;
    int counted = 0;
    for (const std::string& s : sequences) {
      int swept = 0, aut = 0;
      for (std::size_t p = 0; p < run.pairs.size(); ++p) {
        if (run.pairs[p].sequence != s) continue;
        swept += run.results[p][static_cast<std::size_t>(adaptive)].correct;
        aut += run.results[p][static_cast<std::size_t>(automatic)].correct;
      }
      if (swept > 0) {
        ratio_sum += static_cast<double>(aut) / swept;
        ++counted;
      }
    }
    md << "- Pair-free automatic F reaches **"
       << fmt("%.1f%%", counted ? 100 * ratio_sum / counted : 0.0)
       << "** of the swept F's correct matches, averaged over the sequences.\n";
  }

  if (!plot_folder.empty()) {
    md << "\n## Plots\n\n";
    for (const std::string& s : sequences)
      md << "![" << s << "](" << plot_folder << "/" << s << ".png)\n";
  }
  return md.str();
}

std::string json_report(const EvalRun& run) {
  std::ostringstream out;
  io::JsonWriter json(out);
  json.set_newline_depth(3);
  json.begin_object();
  json.field("matcher", run.matcher)
      .field("seconds", run.seconds)
      .field("timing_rounds", run.timing_rounds);
  json.field("load_average_lowest", run.load.lowest)
      .field("load_average_highest", run.load.highest);
  json.key("pairs").begin_array();
  for (std::size_t p = 0; p < run.pairs.size(); ++p) {
    json.begin_object()
        .field("sequence", run.pairs[p].sequence)
        .field("pair", "1-" + std::to_string(run.pairs[p].target));
    json.key("methods").begin_object();
    for (std::size_t m = 0; m < run.methods.size(); ++m) {
      const PairResult& r = run.results[p][m];
      json.key(method_key(run.methods[m])).begin_object();
      json.field("keypoints_a", r.keypoints_a)
          .field("keypoints_b", r.keypoints_b)
          .field("putative", r.putative);
      json.field("inliers", r.inliers)
          .field("cmr", r.cmr)
          .field("correct", r.correct)
          .field("accuracy", r.accuracy);
      json.field("corner_error", r.corner_error)
          .field("homography_ok", r.homography_ok)
          .field("extract_ms", r.extract_ms);
      json.field("extract_min_ms", r.extract_min_ms).field("extract_max_ms", r.extract_max_ms);
      json.field("extract_wall_ms", r.extract_wall_ms);
      json.field("sweep_ms", r.sweep_ms)
          .field("threshold", r.threshold)
          .field("repeatability", r.repeatability);
      json.field("spread", r.spread).end_object();
    }
    json.end_object().end_object();
  }
  json.end_array().end_object();
  return out.str();
}

std::vector<std::string> write_plots(const EvalRun& run, const std::string& folder) {
  std::filesystem::create_directories(folder);
  std::vector<std::string> written;
  for (const std::string& s : sequences_of(run)) {
    io::Plot plot;
    plot.title = s + ": img1 -> imgN";
    plot.x_label = "N, the target image of img1 -> imgN (the transformation grows with N)";
    io::PlotPanel correct{"correct matches (count; within 3 px of the true homography)", {}},
        accuracy{"matching accuracy (% of putative matches)", {}};
    for (std::size_t m = 0; m < run.methods.size(); ++m) {
      io::PlotSeries c{method_name(run.methods[m]), {}, {}}, a{c.label, {}, {}};
      for (std::size_t p = 0; p < run.pairs.size(); ++p) {
        if (run.pairs[p].sequence != s) continue;
        c.x.push_back(run.pairs[p].target);
        a.x.push_back(run.pairs[p].target);
        c.y.push_back(run.results[p][m].correct);
        a.y.push_back(100 * run.results[p][m].accuracy);
      }
      correct.series.push_back(c);
      accuracy.series.push_back(a);
    }
    plot.panels = {correct, accuracy};
    const std::string path = (std::filesystem::path(folder) / (s + ".png")).string();
    io::write_plot_png(path, plot);
    written.push_back(path);
  }
  return written;
}

}  // namespace aief::eval
