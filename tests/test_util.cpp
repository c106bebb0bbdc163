#include "tests/test_util.h"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace srcodec::test {

namespace fs = std::filesystem;

std::string source_path(const std::string& relative) { return std::string(SRCODEC_SOURCE_DIR) + "/" + relative; }
std::string corpus_path(const std::string& name) { return std::string(SRCODEC_CORPUS_DIR) + "/" + name; }
bool have_corpus() { return fs::exists(corpus_path("MANIFEST.md")); }

ScratchDir::ScratchDir() {
  std::string pattern = (fs::temp_directory_path() / "srcodec_test_XXXXXX").string();
  char* made = mkdtemp(pattern.data());
  path_ = made ? made : pattern;
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string ScratchDir::write(const std::string& name, const std::string& contents) const {
  std::ofstream out(file(name), std::ios::binary);
  out << contents;
  return file(name);
}

CommandResult run_srcodec(const std::string& args) { return run_binary(SRCODEC_BINARY, args); }

CommandResult run_binary(const std::string& binary, const std::string& args) {
  ScratchDir dir;
  const std::string command = binary + " " + args + " >" + dir.file("out") + " 2>" +
                              dir.file("err") + " </dev/null";
  const int status = std::system(command.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  auto slurp = [](const std::string& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  r.out = slurp(dir.file("out"));
  r.err = slurp(dir.file("err"));
  return r;
}

TriangleMesh tetrahedron() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

TriangleMesh unit_cube() {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  // Two outward triangles per face.
  m.triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

TriangleMesh flat_square(int n) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.emplace_back(double(i) / n, double(j) / n, 0.0);
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return m;
}

TriangleMesh icosphere(int subdivisions, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh m;
  m.positions = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int32_t, int32_t>, int32_t> midpoints;
    auto mid = [&](int32_t a, int32_t b) {
      auto key = std::minmax(a, b);
      auto it = midpoints.find(key);
      if (it != midpoints.end()) return it->second;
      m.positions.push_back((m.positions[a] + m.positions[b]) / 2);
      return midpoints[key] = static_cast<int32_t>(m.positions.size() - 1);
    };
    std::vector<std::array<int32_t, 3>> next;
    for (const auto& f : m.triangles) {
      const int32_t ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    m.triangles.swap(next);
  }
  for (auto& p : m.positions) p = p.normalized() * radius;
  return m;
}

TriangleMesh waisted_ring(int n, int m) {
  TriangleMesh mesh;
  const double pi = std::acos(-1.0);
  for (int i = 0; i < n; ++i) {
    const double u = 2.0 * pi * i / n;
    const double r = 0.25 - 0.235 * std::exp(-(u - pi) * (u - pi) / 0.1);
    for (int j = 0; j < m; ++j) {
      const double v = 2.0 * pi * j / m;
      const double rho = 1.0 + r * std::cos(v);
      mesh.positions.emplace_back(rho * std::cos(u), rho * std::sin(u), r * std::sin(v));
    }
  }
  auto id = [n, m](int i, int j) { return (i % n) * m + (j % m); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return mesh;
}

std::string shell_quote(const std::string& s) { return "'" + s + "'"; }

double json_number(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": (-?[0-9.eE+-]+)"))) return std::nan("");
  return std::stod(m[1]);
}

// The cube [-1, 1]^3, each face an n x n grid, faces facing out.
TriangleMesh grid_cube(int n) {
  GridBuilder g;
  for (int axis = 0; axis < 3; ++axis)
    for (double s : {-1.0, 1.0})
      g.patch(n, [&](double u, double v) {
        Eigen::Vector3d p;
        p[axis] = s;
        // Swap the grid's directions on one side so both faces face out.
        p[(axis + 1) % 3] = 2 * (s > 0 ? u : v) - 1;
        p[(axis + 2) % 3] = 2 * (s > 0 ? v : u) - 1;
        return p;
      });
  return g.mesh;
}

}  // namespace srcodec::test
