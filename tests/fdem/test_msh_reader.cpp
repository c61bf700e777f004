//! \file test_msh_reader.cpp
//! \brief Mesh files are read as data: MSH 4.1 ASCII parsed without Gmsh, script commands never run, errors
//! with the line number; Gmsh scripts (.geo) refused.
#include "blastsim/core/error.hpp"
#include "blastsim/fdem/gmsh_mesh.hpp"
#include "catch.hpp"

#include <filesystem>
#include <fstream>
#include <string>

using namespace blastsim::fdem;
namespace fs = std::filesystem;

namespace {
const std::string data = BLASTSIM_TEST_DATA_DIR;

//! The bundled square.msh with `insert` placed after its $EndMeshFormat line, written to a temporary file.
fs::path square_with(const std::string& name, const std::string& insert) {
  std::ifstream in(data + "/square.msh");
  std::string text, line;
  while (std::getline(in, line)) {
    text += line + "\n";
    if (line == "$EndMeshFormat") text += insert;
  }
  const fs::path p = fs::temp_directory_path() / ("blastsim_msh_" + name + ".msh");
  std::ofstream(p) << text;
  return p;
}
}  // namespace

TEST_CASE("MSH 4.1 files are read as data, without Gmsh: nodes, triangles, named boundary lines",
          "[fdem][mesh][msh]") {
  const NamedMesh m = read_msh_file(data + "/square.msh");
  REQUIRE(m.mesh.triangles.size() == 2);
  CHECK(m.mesh.vertices.size() == 4);
  REQUIRE(m.boundary_groups.count("left") == 1);
  CHECK(m.boundary_groups.at("left").size() == 1);
  // Sections the reader does not know are skipped as data.
  const NamedMesh n = read_msh_file(square_with("comments", "$Comments\nanything at all 1 2 3\n$EndComments\n").string());
  CHECK(n.mesh.triangles.size() == 2);
}

TEST_CASE("A mesh file never runs commands: script lines are refused or skipped, .geo scripts refused",
          "[fdem][mesh][msh][security]") {
  const fs::path marker = fs::temp_directory_path() / "blastsim_msh_was_run";
  fs::remove(marker);
  const std::string call = "SystemCall \"touch " + marker.string() + "\";\n";
  // A command between sections: an error with its line number, and nothing run.
  const fs::path bad = square_with("call", call);
  CHECK_THROWS_WITH(read_gmsh_file(bad.string()), Catch::Contains("line 4") && Catch::Contains("section"));
  // Inside a section nobody reads: skipped as data.
  const fs::path hidden = square_with("hidden", "$Script\n" + call + "$EndScript\n");
  CHECK(read_gmsh_file(hidden.string()).mesh.triangles.size() == 2);
  CHECK_FALSE(fs::exists(marker));
  // A Gmsh script is refused by name, whatever it holds.
  const fs::path geo = fs::temp_directory_path() / "blastsim_msh_case.geo";
  std::ofstream(geo) << call;
  CHECK_THROWS_WITH(read_gmsh_file(geo.string()), Catch::Contains("script"));
  CHECK_FALSE(fs::exists(marker));
}

TEST_CASE("Malformed mesh files give an error with the line and what was expected", "[fdem][mesh][msh][errors]") {
  const fs::path p = fs::temp_directory_path() / "blastsim_msh_bad.msh";
  std::ofstream(p) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n0 1 0 1\n1\n0 zero 0\n$EndNodes\n";
  CHECK_THROWS_WITH(read_msh_file(p.string()), Catch::Contains("line 8") && Catch::Contains("not a number"));
  std::ofstream(p, std::ios::trunc) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  CHECK_THROWS_WITH(read_msh_file(p.string()), Catch::Contains("4.1"));
  std::ofstream(p, std::ios::trunc) << "$MeshFormat\n4.1 1 8\n$EndMeshFormat\n";
  CHECK_THROWS_WITH(read_msh_file(p.string()), Catch::Contains("binary"));
  std::ofstream(p, std::ios::trunc) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n0 1 0 1\n1\n0 0 0\n"
                                       "$EndNodes\n$Elements\n1 1 1 1\n2 1 2 1\n1 1 2 3\n$EndElements\n";
  CHECK_THROWS_WITH(read_msh_file(p.string()), Catch::Contains("node 2"));
  CHECK_THROWS_AS(read_msh_file((fs::temp_directory_path() / "blastsim_no_such.msh").string()), blastsim::InputError);
}
