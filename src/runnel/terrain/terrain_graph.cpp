// SPDX-License-Identifier: MIT
#include "runnel/terrain/terrain_graph.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include "runnel/core/error.hpp"
#include "runnel/core/input_file.hpp"
#include "runnel/terrain/filters.hpp"
#include "runnel/terrain/generators.hpp"
#include "runnel/terrain/terrain_io.hpp"

namespace runnel {
namespace {

struct Node {
  std::string name;
  const toml::table* table = nullptr;
  std::vector<std::string> inputs;
};

double number(const toml::node& node, const std::string& where) {
  if (node.is_integer()) return static_cast<double>(node.as_integer()->get());
  if (node.is_floating_point()) return node.as_floating_point()->get();
  throw input_error(where + ": expected a number");
}

std::string text(const toml::table& t, const std::string& key, const std::string& where) {
  const toml::node* n = t.get(key);
  if (!n) return "";
  if (!n->is_string()) throw input_error(where + "." + key + ": expected a string");
  return n->as_string()->get();
}

class Graph {
 public:
  Graph(const toml::table& root, std::string origin, std::string base_dir, ComputeContext* compute)
      : origin_(std::move(origin)), base_dir_(std::move(base_dir)), compute_(compute) {
    read_grid(root);
    const toml::table* nodes = root["nodes"].as_table();
    if (!nodes || nodes->empty()) throw input_error(origin_ + ": no [nodes.NAME] tables");
    for (auto&& [key, value] : *nodes) {
      const std::string name(key.str());
      const std::string where = origin_ + " nodes." + name;
      if (!value.is_table()) throw input_error(where + ": expected a table");
      Node node{name, value.as_table(), {}};
      const toml::table& t = *node.table;
      if (const toml::node* one = t.get("input")) {
        if (!one->is_string()) throw input_error(where + ".input: expected a node name");
        node.inputs.push_back(one->as_string()->get());
      }
      if (const toml::node* many = t.get("inputs")) {
        const toml::array* list = many->as_array();
        if (!list) throw input_error(where + ".inputs: expected a list of node names");
        for (const toml::node& n : *list) {
          if (!n.is_string()) throw input_error(where + ".inputs: expected node names");
          node.inputs.push_back(n.as_string()->get());
        }
      }
      nodes_[name] = node;
    }
    output_ = text(root, "output", origin_);
    if (output_.empty()) throw input_error(origin_ + " output: name the node that is the terrain");
    if (!nodes_.count(output_))
      throw input_error(origin_ + " output: no node named '" + output_ + "'");
    for (auto& [name, node] : nodes_)
      for (const std::string& input : node.inputs)
        if (!nodes_.count(input))
          throw input_error(origin_ + " nodes." + name + ": input '" + input + "' is not a node");
    refuse_cycles();
    for (auto&& [key, value] : root) {
      const std::string k(key.str());
      if (k != "size" && k != "cell" && k != "seed" && k != "output" && k != "nodes")
        throw input_error(origin_ + " " + k + ": unknown key (size, cell, seed, output, nodes)");
    }
  }

  Heightmap evaluate() { return value(output_); }

 private:
  void read_grid(const toml::table& root) {
    if (const toml::node* size = root.get("size")) {
      if (const toml::array* two = size->as_array()) {
        if (two->size() != 2) throw input_error(origin_ + " size: expected N or [NX, NY]");
        nx_ = static_cast<int>(number(*two->get(0), origin_ + " size"));
        ny_ = static_cast<int>(number(*two->get(1), origin_ + " size"));
      } else {
        nx_ = ny_ = static_cast<int>(number(*size, origin_ + " size"));
      }
    }
    if (const toml::node* cell = root.get("cell")) cell_ = number(*cell, origin_ + " cell");
    if (const toml::node* seed = root.get("seed")) {
      const double s = number(*seed, origin_ + " seed");
      if (s < 0) throw input_error(origin_ + " seed: must be ≥ 0");
      seed_ = static_cast<std::uint64_t>(s);
    }
    if (!(cell_ > 0) || !std::isfinite(cell_))
      throw input_error(origin_ + " cell: must be a positive number of metres");
  }

  // Depth-first search with three colours; a grey node met again closes a cycle, named in order.
  void refuse_cycles() {
    std::map<std::string, int> colour;  // 0 white, 1 grey, 2 black
    std::vector<std::string> path;
    std::function<void(const std::string&)> visit = [&](const std::string& name) {
      colour[name] = 1;
      path.push_back(name);
      for (const std::string& input : nodes_[name].inputs) {
        if (colour[input] == 1) {
          std::string cycle;
          const auto start = std::find(path.begin(), path.end(), input);
          for (auto it = start; it != path.end(); ++it) cycle += *it + " → ";
          throw input_error(origin_ + ": the graph has a cycle: " + cycle + input);
        }
        if (colour[input] == 0) visit(input);
      }
      path.pop_back();
      colour[name] = 2;
    };
    for (auto& entry : nodes_)
      if (colour[entry.first] == 0) visit(entry.first);
  }

  const Heightmap& value(const std::string& name) {
    auto done = values_.find(name);
    if (done != values_.end()) return done->second;
    const Node& node = nodes_.at(name);
    const std::string where = origin_ + " nodes." + name;
    const toml::table& t = *node.table;
    const std::string generator = text(t, "generator", where), filter = text(t, "filter", where),
                      file = text(t, "file", where);
    if (int(!generator.empty()) + int(!filter.empty()) + int(!file.empty()) != 1)
      throw input_error(where + ": give exactly one of generator, filter or file");
    Heightmap result;
    if (!generator.empty()) {
      result = generate(t, generator, where);
    } else if (!file.empty()) {
      result = read(t, file, where);
    } else {
      result = apply(t, filter, node, where);
    }
    return values_[name] = std::move(result);
  }

  Heightmap generate(const toml::table& t, const std::string& generator, const std::string& where) {
    std::map<std::string, double> set;
    std::uint64_t seed = seed_;
    for (auto&& [key, v] : t) {
      const std::string k(key.str());
      if (k == "generator") continue;
      if (k == "seed") {
        seed = static_cast<std::uint64_t>(number(v, where + ".seed"));
      } else if (k == "set") {
        if (!v.is_table())
          throw input_error(where + ".set: expected a table of generator parameters");
        for (auto&& [pk, pv] : *v.as_table())
          set[std::string(pk.str())] = number(pv, where + ".set." + std::string(pk.str()));
      } else {
        throw input_error(where + "." + k +
                          ": unknown key of a generator node (generator, seed, set)");
      }
    }
    try {
      return generate_terrain(generator, nx_, ny_, cell_, seed, set, compute_);
    } catch (const Error& e) {
      std::string msg = e.what();
      if (msg.rfind("--set ", 0) == 0) msg = where + ".set." + msg.substr(6);
      throw Error(e.code(), msg);
    }
  }

  Heightmap read(const toml::table& t, const std::string& file, const std::string& where) {
    for (auto&& [key, v] : t)
      if (key.str() != "file")
        throw input_error(where + "." + std::string(key.str()) + ": unknown key of a file node");
    std::filesystem::path path(file);
    if (path.is_relative() && !base_dir_.empty()) path = std::filesystem::path(base_dir_) / path;
    Heightmap h(nx_, ny_, cell_);
    h.h = read_vertex_raster(path.lexically_normal().string(), nx_, ny_, where + ".file");
    return h;
  }

  Heightmap apply(const toml::table& t, const std::string& filter, const Node& node,
                  const std::string& where) {
    const FilterSpec* spec = find_filter(filter);
    if (!spec) {
      std::string names;
      for (const FilterSpec& f : filters()) names += (names.empty() ? "" : ", ") + f.name;
      throw input_error(where + ".filter: unknown filter '" + filter + "' (known: " + names + ")");
    }
    const int count = static_cast<int>(node.inputs.size());
    if (count < spec->min_inputs || count > spec->max_inputs)
      throw input_error(where + ": filter " + filter + " takes " +
                        std::to_string(spec->min_inputs) +
                        (spec->max_inputs > spec->min_inputs ? " or more" : "") + " input" +
                        (spec->min_inputs > 1 ? "s" : "") + ", got " + std::to_string(count));
    std::map<std::string, double> values;
    for (const FilterParam& p : spec->params) values[p.key] = p.default_value;
    for (auto&& [key, v] : t) {
      const std::string k(key.str());
      if (k == "filter" || k == "input" || k == "inputs") continue;
      const auto it = std::find_if(spec->params.begin(), spec->params.end(),
                                   [&k](const FilterParam& p) { return p.key == k; });
      if (it == spec->params.end())
        throw input_error(where + "." + k + ": not a parameter of filter " + filter);
      const double x = number(v, where + "." + k);
      if (!std::isfinite(x) || x < it->min_value || x > it->max_value) {
        std::ostringstream msg;
        msg << where << "." << k << ": " << x << " is outside [" << it->min_value << ", "
            << it->max_value << "]";
        throw input_error(msg.str());
      }
      values[k] = x;
    }
    std::vector<const Heightmap*> inputs;
    for (const std::string& input : node.inputs) inputs.push_back(&value(input));
    return spec->apply(inputs, values);
  }

  std::string origin_, base_dir_;
  ComputeContext* compute_;
  int nx_ = 257, ny_ = 257;
  double cell_ = 1.0;
  std::uint64_t seed_ = 1;
  std::string output_;
  std::map<std::string, Node> nodes_;
  std::map<std::string, Heightmap> values_;
};

}  // namespace

Heightmap evaluate_terrain_graph_text(const std::string& toml_text, const std::string& origin,
                                      const std::string& base_dir, ComputeContext* compute) {
  toml::table root;
  try {
    check_toml_key_depth(toml_text, origin);
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& e) {
    throw input_error(origin + ":" + std::to_string(e.source().begin.line) +
                      ": TOML syntax error: " + std::string(e.description()));
  }
  Graph graph(root, origin, base_dir, compute);
  Heightmap h = graph.evaluate();
  for (float v : h.h)
    if (!std::isfinite(v))
      throw input_error(origin + ": the graph's output holds a non-finite height");
  return h;
}

Heightmap evaluate_terrain_graph(const std::string& path, ComputeContext* compute) {
  return evaluate_terrain_graph_text(read_text_input(path, "terrain graph"), path,
                                     std::filesystem::path(path).parent_path().string(), compute);
}

}  // namespace runnel
