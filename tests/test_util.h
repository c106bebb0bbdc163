// Shared helpers for the tests: paths to the sample and corpus meshes, small
// meshes built in code, a scratch folder, and running the srcodec binary.
#pragma once

#include <array>
#include <cmath>
#include <map>
#include <string>

#include "format/mesh.h"

namespace srcodec::test {

std::string source_path(const std::string& relative);  // inside the repository
std::string corpus_path(const std::string& name);      // ../shared/data/meshes/name
bool have_corpus();

// A fresh folder, removed with everything in it when the object goes.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  // Writes `contents` to file(name) and returns its path.
  std::string write(const std::string& name, const std::string& contents) const;

 private:
  std::string path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};
// Runs `binary` with `args` (shell-quoted by the caller).
CommandResult run_binary(const std::string& binary, const std::string& args);
// Runs the srcodec binary with `args`.
CommandResult run_srcodec(const std::string& args);
std::string shell_quote(const std::string& s);  // 's' for paths without quotes
// A number field of a flat JSON line, NaN if absent.
double json_number(const std::string& json, const std::string& key);

// Small meshes with known answers.
TriangleMesh tetrahedron();
TriangleMesh unit_cube();                   // closed, 8 vertices, 12 triangles
TriangleMesh flat_square(int n);            // open n x n grid in z = 0, 1 boundary loop
TriangleMesh icosphere(int subdivisions, double radius);
// A ring (circle of radius 1) of tube of radius 0.25 except for a short
// waist of radius 0.015; n x m vertices, closed, genus 1.
TriangleMesh waisted_ring(int n, int m);

// A mesh from a grid of n x n quads per patch, each patch a map from [0, 1]^2
// into space; vertices at the same place are one.
class GridBuilder {
 public:
  template <class Map>
  void patch(int n, Map&& at) {
    std::vector<int32_t> index((n + 1) * (n + 1));
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) index[i * (n + 1) + j] = vertex(at(double(i) / n, double(j) / n));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int32_t a = index[i * (n + 1) + j], b = index[(i + 1) * (n + 1) + j];
        const int32_t c = index[(i + 1) * (n + 1) + j + 1], d = index[i * (n + 1) + j + 1];
        mesh.triangles.push_back({a, b, c});
        mesh.triangles.push_back({a, c, d});
      }
  }
  TriangleMesh mesh;

 private:
  int32_t vertex(const Eigen::Vector3d& p) {
    const std::array<long long, 3> key{std::llround(p.x() * 1e6), std::llround(p.y() * 1e6), std::llround(p.z() * 1e6)};
    const auto [it, added] = where_.emplace(key, static_cast<int32_t>(mesh.positions.size()));
    if (added) mesh.positions.push_back(p);
    return it->second;
  }
  std::map<std::array<long long, 3>, int32_t> where_;
};

// The cube [-1, 1]^3, each face an n x n grid, faces facing out.
TriangleMesh grid_cube(int n);

}  // namespace srcodec::test
