// SPDX-License-Identifier: MIT
#include "runnel/sweep/sweep.hpp"

#include <toml++/toml.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "runnel/compute/context.hpp"
#include "runnel/core/error.hpp"
#include "runnel/core/input_file.hpp"
#include "runnel/core/text.hpp"
#include "runnel/io/atomic_file.hpp"
#include "runnel/metrics/terrain_metrics.hpp"
#include "runnel/models/checkpoint.hpp"
#include "runnel/models/registry.hpp"
#include "runnel/sim/run.hpp"
#include "runnel/sim/scenario.hpp"
#include "runnel/terrain/terrain_io.hpp"
#include "runnel/terrain/terrain_source.hpp"

namespace runnel {

namespace fs = std::filesystem;

namespace {

const char* kRunMetrics[] = {
    "eroded_volume",    "deposited_volume", "outflow_volume", "suspended_volume", "rain_volume",
    "mass_balance_abs", "mass_balance_rel", "steps",          "sim_time"};

// The shortest of %.15g .. %.17g that reads back as the same double: 0.01, not
// 0.01000000000000000021.
std::string number_text(double v) {
  char buf[40];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

// A TOML value as parameter text (what --set takes).
std::string value_text(const toml::node& node, const std::string& where) {
  if (auto s = node.value<std::string>(); s && node.is_string()) return *s;
  if (node.is_integer()) return std::to_string(node.as_integer()->get());
  if (node.is_floating_point()) return number_text(node.as_floating_point()->get());
  if (node.is_boolean()) return node.as_boolean()->get() ? "true" : "false";
  throw input_error(where + ": a value must be a string, number or boolean");
}

// The short axis names researchers write, and the parameter each stands for.
std::string axis_key(const std::string& name) {
  if (name == "model") return "run.model";
  if (name == "seed") return "run.seed";
  if (name == "terrain") return "terrain.file";
  return name;
}

SweepAxis read_axis(const std::string& key, const toml::node& node, const std::string& where,
                    const fs::path& sweep_dir) {
  SweepAxis axis{axis_key(key), {}};
  if (!find_param(axis.key)) throw input_error(where + ": unknown parameter (see 'runnel params')");
  if (auto* list = node.as_array()) {
    for (const auto& v : *list) axis.values.push_back(value_text(v, where));
  } else if (auto* range = node.as_table()) {
    // { from = A, to = B, count = N }: N values evenly from A to B (integers stay integers).
    for (auto&& [k, v] : *range) {
      if (k.str() != "from" && k.str() != "to" && k.str() != "count")
        throw input_error(where + ": a range has from, to and count, not " + std::string(k.str()));
    }
    const auto from = (*range)["from"].value<double>(), to = (*range)["to"].value<double>();
    const auto count = (*range)["count"].value<std::int64_t>();
    if (!from || !to || !count) throw input_error(where + ": a range needs from, to and count");
    if (*count < 1 || *count > 100000) throw input_error(where + ": count must be 1 to 100000");
    const bool integers = (*range)["from"].is_integer() && (*range)["to"].is_integer();
    for (std::int64_t k = 0; k < *count; ++k) {
      const double v =
          *count == 1 ? *from : *from + (*to - *from) * static_cast<double>(k) / (*count - 1);
      axis.values.push_back(integers ? std::to_string(std::llround(v)) : number_text(v));
    }
  } else {
    throw input_error(where + ": an axis is a list of values ([" + value_text(node, where) +
                      "]) or a range { from, to, count }; a value every member shares belongs in "
                      "the base scenario");
  }
  if (axis.values.empty()) throw input_error(where + ": the axis has no values");
  if (axis.key == "terrain.file") {
    for (std::string& file : axis.values) {
      if (fs::path(file).is_relative()) file = (sweep_dir / file).lexically_normal().string();
      std::error_code ec;
      if (!fs::is_regular_file(file, ec)) throw input_error(where + ": " + file + ": no such file");
      terrain_format_from_path(file);
    }
  }
  return axis;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The newest step_XXXXXXXX.h5 in `dir` (names sort by step), or "" when there is none.
std::string newest_checkpoint(const fs::path& dir) {
  std::error_code ec;
  std::string newest;
  if (!fs::is_directory(dir, ec)) return newest;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("step_", 0) == 0 && e.path().extension() == ".h5" && e.path().string() > newest)
      newest = e.path().string();
  }
  return newest;
}

}  // namespace

std::vector<std::string> sweep_metric_names() {
  std::vector<std::string> names(std::begin(kRunMetrics), std::end(kRunMetrics));
  const Heightmap probe(4, 4, 1.0);
  for (const auto& [name, value] : metrics::terrain_metric_values(probe, probe))
    names.push_back(name);
  for (const ModelEntry& model : model_registry())
    for (const std::string& name : model.info().summary_names)
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  return names;
}

SweepSpec read_sweep(const std::string& path) {
  SweepSpec spec;
  spec.path = path;
  const std::string text = read_text_input(path, "sweep file");
  check_toml_key_depth(text, path);
  toml::table table;
  try {
    table = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw input_error(path + ":" + std::to_string(e.source().begin.line) +
                      ": TOML syntax error: " + std::string(e.description()));
  }
  const fs::path dir = fs::path(path).parent_path();
  for (auto&& [k, node] : table) {
    if (k.str() != "sweep" && k.str() != "axes")
      throw input_error(path + ": unknown table or key '" + std::string(k.str()) +
                        "' (sweep, axes)");
  }
  spec.metrics = {"eroded_volume",    "deposited_volume",     "outflow_volume",
                  "mass_balance_abs", "hypsometric_integral", "erosion_flow_correlation"};
  if (auto* sweep = table["sweep"].as_table()) {
    for (auto&& [k, node] : *sweep) {
      const std::string key(k.str()), where = path + ": sweep." + key;
      if (key == "base") {
        const auto base = node.value<std::string>();
        if (!base) throw input_error(where + ": a scenario file name");
        spec.base = load_scenario(fs::path(*base).is_relative() ? (dir / *base).string() : *base);
      } else if (key == "combine") {
        const auto combine = node.value<std::string>();
        if (!combine || (*combine != "grid" && *combine != "zip"))
          throw input_error(where + ": \"grid\" or \"zip\"");
        spec.zip = *combine == "zip";
      } else if (key == "metrics") {
        auto* list = node.as_array();
        if (!list || list->empty()) throw input_error(where + ": a non-empty list of metric names");
        const auto known = sweep_metric_names();
        spec.metrics.clear();
        for (const auto& m : *list) {
          const std::string name = value_text(m, where);
          if (std::find(known.begin(), known.end(), name) == known.end())
            throw input_error(where + ": unknown metric '" + name + "'");
          spec.metrics.push_back(name);
        }
      } else if (key == "checkpoint_every") {
        const auto every = node.value<std::int64_t>();
        if (!every || *every < 0) throw input_error(where + ": a step count, 0 for none");
        spec.checkpoint_every = *every;
      } else if (key == "max_members") {
        const auto max = node.value<std::int64_t>();
        if (!max || *max < 1) throw input_error(where + ": a positive integer");
        spec.max_members = *max;
      } else {
        throw input_error(where +
                          ": unknown key (base, combine, metrics, max_members, checkpoint_every)");
      }
    }
  }
  auto* axes = table["axes"].as_table();
  if (!axes || axes->empty())
    throw input_error(path + ": [axes] names at least one parameter to vary");
  for (auto&& [k, node] : *axes) {
    spec.axes.push_back(
        read_axis(std::string(k.str()), node, path + ": axes." + std::string(k.str()), dir));
    for (std::size_t a = 0; a + 1 < spec.axes.size(); ++a)
      if (spec.axes[a].key == spec.axes.back().key)
        throw input_error(path + ": axes." + std::string(k.str()) + " and another axis both vary " +
                          spec.axes.back().key +
                          " (model, seed and terrain are short for run.model, "
                          "run.seed and terrain.file): give one");
  }
  if (spec.zip) {
    for (const SweepAxis& a : spec.axes) {
      if (a.values.size() != spec.axes.front().values.size())
        throw input_error(path + ": combine = \"zip\" needs axes of one length (" + a.key +
                          " has " + std::to_string(a.values.size()) + ")");
    }
  }
  return spec;
}

long long sweep_member_count(const SweepSpec& spec) {
  if (spec.zip) return std::min<long long>(spec.axes.front().values.size(), kMaxSweepMembers + 1);
  long long count = 1;
  for (const SweepAxis& a : spec.axes) {
    const auto n = static_cast<long long>(a.values.size());
    if (n == 0) return 0;
    count = count > (kMaxSweepMembers + 1) / n ? kMaxSweepMembers + 1 : count * n;
  }
  return std::min(count, kMaxSweepMembers + 1);
}

std::vector<SweepMember> expand_sweep(const SweepSpec& spec) {
  const long long total = sweep_member_count(spec);
  if (total > kMaxSweepMembers)
    throw input_error(spec.path + ": more than " + std::to_string(kMaxSweepMembers) +
                      " members; split the sweep");
  const auto count = static_cast<std::size_t>(total);
  std::vector<SweepMember> members(count);
  for (std::size_t m = 0; m < count; ++m) {
    SweepMember& member = members[m];
    member.index = m;
    member.params = spec.base;
    // Grid: the last axis varies fastest.
    std::size_t rest = m;
    member.values.resize(spec.axes.size());
    for (std::size_t a = spec.axes.size(); a-- > 0;) {
      const auto& values = spec.axes[a].values;
      const std::size_t pick = spec.zip ? m : rest % values.size();
      if (!spec.zip) rest /= values.size();
      member.values[a] = values[pick];
    }
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      member.params.set_text(spec.axes[a].key, member.values[a],
                             spec.path + ": axes." + spec.axes[a].key);
    }
    const ModelClock clock = model_entry(member.params.text("run.model")).info().clock;
    try {
      require_run_length(member.params, clock);
    } catch (const Error& e) {
      throw input_error(spec.path + ": member " + std::to_string(m) + ": " + e.what());
    }
  }
  return members;
}

void claim_sweep_folder(const std::string& out, const std::vector<SweepMember>& members,
                        bool extend) {
  const std::string id = sweep_id(members);
  const fs::path id_file = fs::path(out) / "sweep.id";
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec || !fs::is_directory(out))
    throw input_error("--out " + out + ": cannot create the folder");
  if (fs::exists(id_file, ec)) {
    const std::string old = read_text(id_file).substr(0, 16);
    if (old == id) return;
    if (!extend) {
      throw input_error("--out " + out + ": holds another sweep (" + old + ", this is " + id +
                        "); use another folder, or --extend if this one only adds members");
    }
    for (const SweepMember& m : members) {
      const fs::path scenario = fs::path(member_dir(out, m.index)) / "scenario.toml";
      if (fs::exists(scenario, ec) && read_text(scenario) != parameters_toml(m.params)) {
        throw input_error("--extend: member " + std::to_string(m.index) + " of the sweep in " +
                          out + " has other parameters now");
      }
    }
  }
  write_text_atomically(id_file.string(), id + "\n");
}

std::string sweep_id(const std::vector<SweepMember>& members) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const SweepMember& m : members) {
    for (unsigned char c : parameters_toml(m.params)) h = (h ^ c) * 0x100000001b3ULL;
  }
  char id[24];
  std::snprintf(id, sizeof id, "%016llx", static_cast<unsigned long long>(h));
  return id;
}

std::string member_dir(const std::string& out, std::size_t index) {
  char name[16];
  std::snprintf(name, sizeof name, "%04zu", index);
  return (fs::path(out) / "members" / name).string();
}

MemberState member_state(const std::string& out, std::size_t index, std::string* message) {
  const fs::path dir = member_dir(out, index);
  std::error_code ec;
  if (fs::is_regular_file(dir / "result.csv", ec)) return MemberState::kDone;
  if (fs::is_regular_file(dir / "failed", ec)) {
    if (message) *message = read_text(dir / "failed");
    return MemberState::kFailed;
  }
  return MemberState::kPending;
}

void run_member(const SweepSpec& spec, const SweepMember& member, const std::string& out,
                bool quiet) {
  const fs::path dir = member_dir(out, member.index);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw input_error(dir.string() + ": cannot create the member folder");
  fs::remove(dir / "failed", ec);
  fs::remove(dir / "result.csv", ec);
  write_text_atomically((dir / "scenario.toml").string(), parameters_toml(member.params));
  try {
    // One per process: every member of a worker shares its kernels. Never destroyed: a context
    // released by the exit handlers, after the OpenCL implementation's own statics, can crash it.
    static ComputeContext& compute = *new ComputeContext;
    // An interrupted member goes on from its newest checkpoint (bit for bit the run it would have
    // been).
    const std::string checkpoint = newest_checkpoint(dir / "checkpoints");
    const CheckpointData resumed =
        checkpoint.empty() ? CheckpointData{} : read_checkpoint(checkpoint);
    // Only this member's own run is resumed: a checkpoint of other parameters or another model
    // placed in its folder is refused, not continued as if it were the member.
    if (!checkpoint.empty() &&
        (resumed.model != member.params.text("run.model") ||
         run_identity(resumed.parameters_toml) != run_identity(parameters_toml(member.params))))
      throw input_error(checkpoint + ": the checkpoint of another run (" + resumed.model +
                        " model, other parameters), not this member's; remove it to run the "
                        "member from its start");
    const std::unique_ptr<Model> model =
        checkpoint.empty() ? make_model(compute, member.params, load_terrain(member.params))
                           : make_model_from_checkpoint(compute, resumed, checkpoint);
    RunOptions options = run_options_from(member.params, model->info().clock);
    options.resumed_counters = resumed.model_counters;
    options.out_dir = dir.string();
    options.quiet = quiet;
    options.checkpoint_every = spec.checkpoint_every;
    options.overwrite = true;  // an interrupted member's checkpoints are this member's own
    const RunSummary s = run_model(compute, *model, options);
    std::vector<std::pair<std::string, double>> values = {{"eroded_volume", s.balance.eroded},
                                                          {"deposited_volume", s.balance.deposited},
                                                          {"outflow_volume", s.balance.outflow},
                                                          {"suspended_volume", s.balance.suspended},
                                                          {"rain_volume", s.rain_volume},
                                                          {"mass_balance_abs", s.balance.residual},
                                                          {"mass_balance_rel", s.balance.relative},
                                                          {"steps", static_cast<double>(s.steps)},
                                                          {"sim_time", s.sim_time}};
    values.insert(values.end(), s.terrain_values.begin(), s.terrain_values.end());
    values.insert(values.end(), s.model_values.begin(), s.model_values.end());
    std::string row = std::to_string(member.index);
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
    for (const std::string& v : member.values) row.append(",").append(csv_field(v));
    for (const std::string& metric : spec.metrics) {
      // A model's own figure that this member's model does not have stays an empty field.
      row.append(",");
      for (const auto& [name, value] : values)
        if (name == metric) row.append(number_text(value));
    }
    // Written last: the member is done only once every output is complete.
    write_text_atomically((dir / "result.csv").string(), row + "\n");
  } catch (const Error& e) {
    write_text_atomically((dir / "failed").string(), std::string(e.what()) + "\n");
    throw;
  }
}

void write_sweep_tables(const SweepSpec& spec, const std::vector<SweepMember>& members,
                        const std::string& out, const std::vector<std::size_t>& running) {
  std::string header = "member";
  for (const SweepAxis& a : spec.axes) header.append(",").append(csv_field(a.key));
  std::string manifest = header + ",state,message\n", results = header;
  for (const std::string& m : spec.metrics) results.append(",").append(m);
  results += "\n";
  for (const SweepMember& m : members) {
    std::string row = std::to_string(m.index);
    for (const std::string& v : m.values) row.append(",").append(csv_field(v));
    std::string message;
    MemberState state = member_state(out, m.index, &message);
    if (state == MemberState::kPending &&
        std::find(running.begin(), running.end(), m.index) != running.end())
      state = MemberState::kRunning;
    static const char* names[] = {"pending", "running", "done", "failed"};
    while (!message.empty() && message.back() == '\n') message.pop_back();
    manifest += row + "," + names[static_cast<int>(state)] + "," + csv_field(message) + "\n";
    if (state == MemberState::kDone)
      results += read_text(fs::path(member_dir(out, m.index)) / "result.csv");
  }
  write_text_atomically((fs::path(out) / "manifest.csv").string(), manifest);
  write_text_atomically((fs::path(out) / "results.csv").string(), results);
}

namespace {

// A word for bash: in single quotes, each ' written as '\''. Nothing inside is expanded.
std::string shell_word(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A value on an #SBATCH line, which sbatch reads itself (no shell): in double quotes, with '%'
// doubled (sbatch's file-name patterns). Text sbatch cannot carry there is refused.
std::string sbatch_value(const std::string& text, const std::string& what) {
  std::string out = "\"";
  for (unsigned char c : text) {
    if (c < 0x20 || c == 0x7f || c == '"' || c == '\\')
      throw input_error(what + " " + runnel::quoted(text) +
                        ": a control byte, a double quote or a backslash cannot go into an "
                        "#SBATCH line; choose a plainer name");
    out += c == '%' ? std::string("%%") : std::string(1, static_cast<char>(c));
  }
  return out + "\"";
}

// SLURM's time formats: minutes, MM:SS, HH:MM:SS, D-HH, D-HH:MM, D-HH:MM:SS.
void check_slurm_time(const std::string& time_limit) {
  const bool plain = !time_limit.empty() && time_limit.size() <= 16 &&
                     time_limit.find_first_not_of("0123456789:-") == std::string::npos &&
                     std::isdigit(static_cast<unsigned char>(time_limit.front())) &&
                     std::isdigit(static_cast<unsigned char>(time_limit.back()));
  if (!plain)
    throw input_error("--time " + runnel::quoted(time_limit) +
                      ": not a SLURM time (minutes, HH:MM:SS or D-HH:MM:SS)");
}

}  // namespace

std::string slurm_script(const SweepSpec& spec, const std::vector<SweepMember>& members,
                         const std::string& out, const std::string& runnel_binary,
                         const std::string& time_limit) {
  check_slurm_time(time_limit);
  const std::string sweep = fs::absolute(spec.path).string(), folder = fs::absolute(out).string();
  const std::string log = sbatch_value(folder + "/slurm-%A_%a.out", "--out");
  // The comments show names as a terminal would (control bytes as \xNN): a newline in a name
  // must not end a comment line and start a command.
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# runnel sweep " << terminal_safe(spec.path) << ": " << members.size()
    << " members, one per array task.\n"
    << "# Submit with: sbatch " << shell_word(terminal_safe(folder + "/sweep.slurm")) << "\n"
    << "# A task whose member is done exits at once, so resubmitting (or a requeue after the time\n"
    << "# limit or a node failure) only redoes unfinished members, from their newest checkpoint "
       "when\n"
    << "# the sweep sets checkpoint_every. Afterwards: runnel sweep "
    << shell_word(terminal_safe(spec.path)) << " --out " << shell_word(terminal_safe(out))
    << " --collect\n"
    << "#SBATCH --job-name=runnel-sweep\n"
    << "#SBATCH --array=0-" << members.size() - 1 << "\n"
    << "#SBATCH --time=" << time_limit << "\n"
    << "#SBATCH --ntasks=1\n"
    << "#SBATCH --requeue\n"
    << "#SBATCH --output=" << log << "\n"
    << "set -euo pipefail\n"
    << "exec " << shell_word(fs::absolute(runnel_binary).string()) << " sweep " << shell_word(sweep)
    << " --out " << shell_word(folder) << " --member \"$SLURM_ARRAY_TASK_ID\" --quiet\n";
  return s.str();
}

}  // namespace runnel
