//! \file msh_reader.cpp
//! \brief Reads a Gmsh mesh file (MSH 4.1, ASCII) as data: nodes, 3-node triangles, and the 2-node lines of
//! named physical curves. Nothing in the file is interpreted as a command (Gmsh's own reader would run the
//! script commands a .msh may carry); errors name the file, the line and what was expected.
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/gmsh_mesh.hpp"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

namespace blastsim::fdem {

namespace {

//! Line-by-line reader of whitespace-separated tokens with the position for messages.
class MshLexer {
 public:
  MshLexer(std::istream& in, std::string path) : in_(in), path_(std::move(path)) {}
  //! The next non-empty line (false at the end of the file).
  bool next_line(std::string& line) {
    while (std::getline(in_, line)) {
      ++line_no_;
      if (line.size() > 1 << 20) fail("a line longer than 1 MiB");
      if (line.find_first_not_of(" \t\r") != std::string::npos) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        return true;
      }
    }
    return false;
  }
  std::string expect_line(const char* what) {
    std::string line;
    if (!next_line(line)) fail(std::string("the file ends where ") + what + " was expected");
    return line;
  }
  //! The numbers of the next line, exactly `count` of them (or at least `count` with `at_least`).
  std::vector<double> numbers(std::size_t count, const char* what, bool at_least = false) {
    const std::string line = expect_line(what);
    std::istringstream s(line);
    std::vector<double> v;
    std::string token;
    while (s >> token) {
      char* end = nullptr;
      const double x = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(x))
        fail(std::string("'") + token.substr(0, 40) + "' is not a number (" + what + ")");
      v.push_back(x);
    }
    if (at_least ? v.size() < count : v.size() != count)
      fail(std::string(what) + ": " + std::to_string(count) + (at_least ? " or more" : "") + " numbers expected, " +
           std::to_string(v.size()) + " found");
    return v;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError("mesh file '" + path_ + "', line " + std::to_string(line_no_) + ": " + what);
  }
  int line() const { return line_no_; }

 private:
  std::istream& in_;
  std::string path_;
  int line_no_ = 0;
};

//! A count from the file: a whole number in [0, limit].
std::size_t count_of(const MshLexer& lex, double v, const char* what, double limit = 1e9) {
  if (!(v >= 0 && v <= limit && v == std::floor(v))) lex.fail(std::string(what) + " is not a count in [0, 1e9]");
  return static_cast<std::size_t>(v);
}

}  // namespace

NamedMesh read_msh_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("mesh file '" + path + "' not found or not readable");
  MshLexer lex(in, path);
  std::map<int, std::string> curve_names;                 // physical tag of dimension 1 -> name
  std::unordered_map<int, std::vector<int>> curve_groups;  // curve entity -> its physical tags
  std::unordered_map<std::uint64_t, std::array<double, 2>> nodes;
  std::vector<std::array<std::uint64_t, 3>> triangles;
  std::vector<std::pair<int, std::array<std::uint64_t, 2>>> lines;  // curve entity, its two nodes
  bool format = false, have_nodes = false, have_elements = false;
  std::string line;
  while (lex.next_line(line)) {
    if (line.empty() || line[0] != '$') lex.fail("a section ($Name) was expected, found '" + line.substr(0, 40) + "'");
    const std::string section = line.substr(1);
    const std::string end = "$End" + section;
    if (section == "MeshFormat") {
      const std::vector<double> f = lex.numbers(3, "version, file type, data size");
      if (f[0] != 4.1) lex.fail("MSH version " + std::to_string(f[0]) + ": only 4.1 is read (save the mesh as MSH 4.1)");
      if (f[1] != 0) lex.fail("a binary mesh file: save it as ASCII MSH 4.1");
      format = true;
    } else if (!format) {
      lex.fail("the file must start with $MeshFormat");
    } else if (section == "PhysicalNames") {
      const std::size_t n = count_of(lex, lex.numbers(1, "number of physical names")[0], "number of physical names");
      for (std::size_t k = 0; k < n; ++k) {
        const std::string l = lex.expect_line("a physical name");
        std::istringstream s(l);
        int dim = 0, tag = 0;
        if (!(s >> dim >> tag)) lex.fail("a physical name: dimension and tag expected");
        const std::size_t q0 = l.find('"'), q1 = l.rfind('"');
        if (q0 == std::string::npos || q1 <= q0) lex.fail("a physical name in double quotes expected");
        if (dim == 1) curve_names[tag] = l.substr(q0 + 1, q1 - q0 - 1);
      }
    } else if (section == "Entities") {
      const std::vector<double> n = lex.numbers(4, "numbers of points, curves, surfaces, volumes");
      for (std::size_t k = 0, m = count_of(lex, n[0], "points"); k < m; ++k) lex.numbers(4, "a point entity", true);
      for (std::size_t k = 0, m = count_of(lex, n[1], "curves"); k < m; ++k) {
        const std::vector<double> c = lex.numbers(8, "a curve entity", true);
        const std::size_t p = count_of(lex, c[7], "physical tags of a curve", 1e6);
        if (c.size() < 8 + p) lex.fail("a curve entity lists fewer physical tags than it says");
        for (std::size_t j = 0; j < p; ++j) curve_groups[static_cast<int>(c[0])].push_back(static_cast<int>(c[8 + j]));
      }
      for (std::size_t k = 0, m = count_of(lex, n[2], "surfaces") + count_of(lex, n[3], "volumes"); k < m; ++k)
        lex.numbers(8, "a surface or volume entity", true);
    } else if (section == "Nodes") {
      const std::vector<double> h = lex.numbers(4, "node blocks, nodes, smallest and largest tag");
      const std::size_t blocks = count_of(lex, h[0], "node blocks");
      for (std::size_t b = 0; b < blocks; ++b) {
        const std::vector<double> bh = lex.numbers(4, "a node block header");
        if (bh[2] != 0) lex.fail("parametric node coordinates are not read (save without them)");
        const std::size_t n = count_of(lex, bh[3], "nodes in a block");
        std::vector<std::uint64_t> tags(n);
        for (std::size_t k = 0; k < n; ++k) tags[k] = count_of(lex, lex.numbers(1, "a node tag")[0], "a node tag", 1e15);
        for (std::size_t k = 0; k < n; ++k) {
          const std::vector<double> x = lex.numbers(3, "node coordinates x y z");
          if (!nodes.emplace(tags[k], std::array<double, 2>{x[0], x[1]}).second)
            lex.fail("node " + std::to_string(tags[k]) + " appears twice");
        }
      }
      have_nodes = true;
    } else if (section == "Elements") {
      const std::vector<double> h = lex.numbers(4, "element blocks, elements, smallest and largest tag");
      const std::size_t blocks = count_of(lex, h[0], "element blocks");
      for (std::size_t b = 0; b < blocks; ++b) {
        const std::vector<double> bh = lex.numbers(4, "an element block header");
        const int dim = static_cast<int>(bh[0]), entity = static_cast<int>(bh[1]), type = static_cast<int>(bh[2]);
        const std::size_t n = count_of(lex, bh[3], "elements in a block");
        const std::size_t per = type == 1 ? 2 : type == 2 ? 3 : type == 15 ? 1 : 0;  // line, triangle, point
        if (per == 0)
          lex.fail("element type " + std::to_string(type) + ": only 2-node lines, 3-node triangles and points are read");
        for (std::size_t k = 0; k < n; ++k) {
          const std::vector<double> e = lex.numbers(per + 1, "an element: its tag and nodes");
          std::array<std::uint64_t, 3> v{};
          for (std::size_t j = 0; j < per; ++j) v[j] = count_of(lex, e[1 + j], "a node tag", 1e15);
          if (type == 2) triangles.push_back(v);
          if (type == 1 && dim == 1) lines.push_back({entity, {v[0], v[1]}});
        }
      }
      have_elements = true;
    } else {
      // Any other section ($Periodic, $NodeData, comments, or script text) is data to skip, never run.
      std::string skipped;
      while (lex.next_line(skipped))
        if (skipped == end) break;
      if (skipped != end) lex.fail("'" + end + "' expected before the end of the file");
      continue;
    }
    if (lex.expect_line(end.c_str()) != end) lex.fail("'" + end + "' expected");
  }
  if (!format || !have_nodes || !have_elements) lex.fail("$MeshFormat, $Nodes and $Elements are all required");
  if (triangles.empty()) lex.fail("no 3-node triangles in the mesh");
  // Vertices numbered in order of first use by the triangles, then by the boundary lines.
  NamedMesh out;
  std::unordered_map<std::uint64_t, int> index;
  auto vertex = [&](std::uint64_t tag) {
    const auto it = index.find(tag);
    if (it != index.end()) return it->second;
    const auto n = nodes.find(tag);
    if (n == nodes.end()) lex.fail("an element refers to node " + std::to_string(tag) + ", which $Nodes does not list");
    const int v = static_cast<int>(out.mesh.vertices.size());
    out.mesh.vertices.push_back(n->second);
    index[tag] = v;
    return v;
  };
  int clockwise = 0;
  for (const auto& t : triangles) {
    const std::array<int, 3> v{vertex(t[0]), vertex(t[1]), vertex(t[2])};
    const auto &a = out.mesh.vertices[v[0]], &b = out.mesh.vertices[v[1]], &c = out.mesh.vertices[v[2]];
    if ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]) < 0) ++clockwise;
    out.mesh.triangles.push_back(v);
  }
  // A surface meshed with its normal along -z gives clockwise triangles throughout: turn them all. A mix is
  // left alone so that check_mesh() reports the inverted ones.
  if (clockwise == static_cast<int>(triangles.size()))
    for (auto& t : out.mesh.triangles) std::swap(t[1], t[2]);
  for (const auto& [entity, l] : lines) {
    const auto groups = curve_groups.find(entity);
    if (groups == curve_groups.end()) continue;
    for (int tag : groups->second) {
      const auto name = curve_names.find(tag);
      out.boundary_groups[name == curve_names.end() ? "group" + std::to_string(tag) : name->second].push_back(
          {vertex(l[0]), vertex(l[1])});
    }
  }
  check_mesh(out.mesh);
  return out;
}

}  // namespace blastsim::fdem
