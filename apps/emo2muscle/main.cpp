// emo2muscle: batch conversion of emotion intensities (ESV) to muscle contraction levels (FMCV) with
// the fuzzy rule-based system of thesis chapter 6. Thin: parse arguments, call fuzzyexpr, write.
#include <iostream>

#include "emoface/cli/cli.hpp"
#include "emoface/core/io.hpp"
#include "emoface/core/version.hpp"
#include "emoface/faceweights/mapper.hpp"
#include "emoface/fuzzyexpr/engine.hpp"
#include "emoface/fuzzyexpr/esv_stream.hpp"
#include "emoface/fuzzyexpr/io.hpp"

namespace fx = emoface::fuzzyexpr;
namespace cli = emoface::cli;
using cli::parse_enum;

int main(int argc, char** argv) {
  CLI::App app{"Convert emotion intensities (ESV: sadness, happiness, anger, fear, disgust, surprise in "
               "[0,1]) to the 19 muscle contraction levels of thesis chapter 6."};
  std::string input = "-", output = "-", from, to, rules_path, mode = "auto", tie = "fixed", weights,
              transition = "crisp", missing = "no_contraction", on_error = "stop", shard_text = "0/1",
              fll_path;
  std::vector<std::string> merge;
  bool sides = false, clamp = false, summary = false;
  std::uint64_t seed = 0;
  int precision = 6;
  app.add_option("input", input, "CSV (header names the emotions) or NDJSON file; - = stdin");
  app.add_option("-o,--output", output, "output file; - = stdout (written atomically)");
  app.add_option("--from", from, "input format csv|ndjson (default: by extension, else csv)");
  app.add_option("--to", to, "output format csv|ndjson|json (default: by extension, else as input)");
  app.add_flag("--sides", sides, "write the 35 left/right face parameters instead of 19 muscles");
  app.add_option("--weights", weights,
                 "facs|arkit: write FACS action units or the 52 ARKit blend shapes instead of "
                 "muscles (data/faceweights)")
      ->check(CLI::IsMember({"facs", "arkit"}));
  app.add_option("--mode", mode, "auto|single|blend expression mode (default auto, thesis 6.5)");
  app.add_option("--rules", rules_path, "rule-base file (default: built-in data/fuzzyexpr/rules.json)");
  app.add_option("--tie-break", tie, "fixed|random choice among equal intensities (default fixed)");
  app.add_option("--seed", seed, "seed of --tie-break random (row r uses stream r)");
  app.add_option("--transition", transition, "crisp|smooth single/blend switch (default crisp)");
  app.add_option("--missing-rule", missing,
                 "reading of '-' cells: no_contraction (default, Table 6.1 caption) or no_rule");
  app.add_option("--on-error", on_error, "stop|skip bad records (default stop: nothing written)");
  app.add_flag("--clamp", clamp, "clamp out-of-range intensities into [0,1] instead of failing");
  app.add_option("--shard", shard_text,
                 "i/N: convert only the i-th of N contiguous blocks of records; auto: from a Slurm "
                 "job array (docs/scale-out.md)");
  app.add_option("--merge", merge,
                 "merge shard outputs (CSV or NDJSON, in shard order) into -o and exit")
      ->expected(1, -1);
  app.add_option("--precision", precision, "decimals of the output levels (1-17, default 6)");
  app.add_option("--export-fll", fll_path, "write the rule base as a fuzzylite FLL engine and exit");
  app.add_flag("--summary", summary, "print one readable line per record (stderr if output is stdout)");
  app.set_version_flag("--version", emoface::kGenerator);
  app.footer(
      "Example:\n  emo2muscle data/fuzzyexpr/example_emotions.csv -o muscles.csv --summary\n"
      "  printf 'id,happiness,surprise,sadness,anger,fear,disgust\\nx,0.8,0.6,0,0,0,0\\n' | "
      "emo2muscle --to ndjson --sides\n"
      "  emo2muscle data/fuzzyexpr/example_emotions.csv --weights arkit -o arkit.csv\n"
      "Exit codes: 0 ok, 1 usage, 2 bad input, 3 numerical, 4 internal.");
  if (auto rc = cli::parse(app, argc, argv)) return *rc;

  return cli::run("emo2muscle", [&] {
    if (!merge.empty()) {
      std::vector<std::string> parts;
      for (const auto& m : merge) parts.push_back(emoface::core::read_file(m));
      cli::Output out(output);
      out.write(emoface::core::merge_shard_outputs(parts));
      out.commit();
      return 0;
    }
    fx::ExpressionOptions options;
    options.mode = parse_enum<fx::ExpressionMode>(mode, fx::expression_mode_from_string, "--mode", "auto|single|blend");
    options.tie_break = parse_enum<fx::TieBreak>(tie, fx::tie_break_from_string, "--tie-break", "fixed|random");
    options.transition = parse_enum<fx::Transition>(transition, fx::transition_from_string, "--transition", "crisp|smooth");
    options.missing_rule = parse_enum<fx::MissingRule>(missing, fx::missing_rule_from_string, "--missing-rule", "no_rule|no_contraction");
    options.seed = seed;
    const fx::RuleBase rules = rules_path.empty() ? fx::default_rule_base() : fx::read_rule_base(rules_path);
    if (!fll_path.empty()) {
      fx::FllOptions fll;
      fll.missing_rule = options.missing_rule;
      emoface::core::write_file_atomic(fll_path, fx::to_fll(rules, fll));
      return 0;
    }
    const fx::Engine engine(rules, options);

    fx::EsvReaderOptions in_opts;
    in_opts.format = from.empty() ? fx::stream_format_from_path(input).value_or(fx::StreamFormat::Csv)
                                  : parse_enum<fx::StreamFormat>(from, fx::stream_format_from_string, "--from", "csv|ndjson");
    in_opts.clamp = clamp;
    fx::FmcvWriterOptions out_opts;
    out_opts.format = to.empty() ? fx::stream_format_from_path(output).value_or(in_opts.format)
                                 : parse_enum<fx::StreamFormat>(to, fx::stream_format_from_string, "--to", "csv|ndjson|json");
    out_opts.sides = sides;
    std::shared_ptr<emoface::faceweights::Mapper> mapper;
    if (!weights.empty()) {
      if (sides) throw cli::UsageError("--weights and --sides exclude each other");
      std::vector<std::string> names;
      for (auto n : fx::side_parameter_names()) names.emplace_back(n);
      mapper = std::make_shared<emoface::faceweights::Mapper>(
          emoface::faceweights::builtin_weight_set(weights), names);
      out_opts.mapped_columns = mapper->set().target_names();
      out_opts.map = [mapper](const fx::SideParameters& s, double* out) {
        mapper->forward(s.data(), out);
      };
    }
    out_opts.precision = precision;
    fx::BatchOptions batch;
    batch.on_error = parse_enum<fx::OnError>(on_error, fx::on_error_from_string, "--on-error", "stop|skip");
    const cli::Shard shard = cli::parse_shard(shard_text);
    batch.shard_index = shard.index;
    batch.shard_count = shard.count;
    if (shard.count > 1 && out_opts.format == fx::StreamFormat::Json)
      throw cli::UsageError("--shard needs a stream output (--to csv or ndjson), not json");

    cli::Input input_stream(input, shard.count > 1);
    std::istream& in = input_stream.stream();
    const std::string& name = input_stream.name();
    if (shard.count > 1) {  // contiguous blocks need the number of records
      fx::EsvReader counter(in, name, in_opts);
      batch.total_records = fx::count_records(counter);
      input_stream.rewind();
    }
    fx::EsvReader reader(in, name, in_opts);
    fx::FmcvWriter writer(out_opts, reader.extra_columns());
    cli::Output out(output);
    std::ostream& notes = out.is_stdout() ? std::cerr : std::cout;
    std::function<void(const fx::EsvRecord&, const fx::Selection&, const fx::Fmcv&)> observer;
    if (summary)
      observer = [&](const fx::EsvRecord& r, const fx::Selection& s, const fx::Fmcv& f) {
        notes << "line " << r.line << ": " << fx::describe(r.esv, s, f) << '\n';
      };
    const auto report = fx::convert_stream(reader, writer, engine, batch,
                                           [&](std::string_view chunk) { out.write(chunk); },
                                           observer);
    out.commit();
    if (report.records_skipped > 0) {
      for (const auto& e : report.errors) std::cerr << "emo2muscle: skipped: " << e << '\n';
      std::cerr << "emo2muscle: skipped " << report.records_skipped << " bad record(s), wrote "
                << report.records_written << '\n';
    }
    if (summary)
      notes << report.records_written << " record(s) converted"
            << (output == "-" ? "" : " to " + output) << '\n';
    return 0;
  });
}
