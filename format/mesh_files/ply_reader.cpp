#include "format/mesh_files/ply_reader.h"

#include <algorithm>
#include <cstring>
#include <sstream>


namespace srcodec {
namespace {

enum class Encoding { kAscii, kLittleEndian, kBigEndian };

struct Property {
  std::string name;
  std::string type;        // scalar type, or the item type of a list
  std::string count_type;  // non-empty for lists
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
};

int type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

class Cursor {
 public:
  Cursor(const std::string& bytes, size_t offset, Encoding enc) : bytes_(bytes), pos_(offset), enc_(enc) {
    if (enc_ == Encoding::kAscii) text_.str(bytes.substr(offset));
  }

  // Reads one value of PLY type `t` as a double.
  Status read(const std::string& t, double* out) {
    if (enc_ == Encoding::kAscii) {
      if (!(text_ >> *out)) return parse_error("ran out of numbers in the ascii body");
      return ok_status();
    }
    const int n = type_size(t);
    if (pos_ + n > bytes_.size()) {
      return parse_error("file ends at byte " + std::to_string(bytes_.size()) + " inside the body");
    }
    unsigned char raw[8];
    std::memcpy(raw, bytes_.data() + pos_, n);
    pos_ += n;
    if (enc_ == Encoding::kBigEndian) std::reverse(raw, raw + n);
    if (t == "char" || t == "int8") *out = static_cast<int8_t>(raw[0]);
    else if (t == "uchar" || t == "uint8") *out = raw[0];
    else if (t == "short" || t == "int16") *out = load<int16_t>(raw);
    else if (t == "ushort" || t == "uint16") *out = load<uint16_t>(raw);
    else if (t == "int" || t == "int32") *out = load<int32_t>(raw);
    else if (t == "uint" || t == "uint32") *out = load<uint32_t>(raw);
    else if (t == "float" || t == "float32") *out = load<float>(raw);
    else *out = load<double>(raw);
    return ok_status();
  }

  size_t remaining_bytes() const { return bytes_.size() - std::min(pos_, bytes_.size()); }

 private:
  template <typename T>
  static double load(const unsigned char* raw) {
    T v;
    std::memcpy(&v, raw, sizeof v);
    return static_cast<double>(v);
  }

  const std::string& bytes_;
  size_t pos_;
  Encoding enc_;
  std::istringstream text_;
};

Status parse_header(const std::string& bytes, Encoding* enc, std::vector<Element>* elements, size_t* body) {
  const size_t end = bytes.find("end_header");
  if (bytes.rfind("ply", 0) != 0 || end == std::string::npos) return parse_error("not a PLY file (no ply/end_header)");
  const size_t eol = bytes.find('\n', end);
  *body = eol == std::string::npos ? bytes.size() : eol + 1;
  std::istringstream header(bytes.substr(0, end));
  std::string line;
  bool have_format = false;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      std::string f;
      words >> f;
      if (f == "ascii") *enc = Encoding::kAscii;
      else if (f == "binary_little_endian") *enc = Encoding::kLittleEndian;
      else if (f == "binary_big_endian") *enc = Encoding::kBigEndian;
      else return parse_error("unknown PLY format '" + f + "'");
      have_format = true;
    } else if (key == "element") {
      Element e;
      if (!(words >> e.name >> e.count)) return parse_error("bad element line '" + line + "'");
      elements->push_back(e);
    } else if (key == "property") {
      if (elements->empty()) return parse_error("property before any element");
      Property p;
      words >> p.type;
      if (p.type == "list") words >> p.count_type >> p.type;
      words >> p.name;
      if (type_size(p.type) == 0 || (!p.count_type.empty() && type_size(p.count_type) == 0))
        return parse_error("unknown property type in '" + line + "'");
      elements->back().properties.push_back(p);
    }
  }
  if (!have_format) return parse_error("PLY header has no format line");
  return ok_status();
}

// Strips restart at -1; every other triangle is flipped to keep the winding.
void add_strip(const std::vector<int64_t>& strip, PolygonMesh* mesh) {
  size_t start = 0;
  for (size_t i = 0; i <= strip.size(); ++i) {
    if (i < strip.size() && strip[i] >= 0) continue;
    for (size_t k = start; k + 2 < i; ++k) {
      int32_t t[3] = {static_cast<int32_t>(strip[k]), static_cast<int32_t>(strip[k + 1]),
                      static_cast<int32_t>(strip[k + 2])};
      if ((k - start) % 2 == 1) std::swap(t[0], t[1]);
      mesh->add_face(t, 3);
    }
    start = i + 1;
  }
}

}  // namespace

Status read_ply(const std::string& bytes, PolygonMesh* mesh) {
  Encoding enc = Encoding::kAscii;
  std::vector<Element> elements;
  size_t body = 0;
  SRCODEC_RETURN_IF_ERROR(parse_header(bytes, &enc, &elements, &body));
  Cursor in(bytes, body, enc);

  for (const Element& e : elements) {
    // Every item takes at least one byte (binary) or two characters (ascii):
    // a count the file cannot hold is rejected before anything is allocated.
    if (e.count > in.remaining_bytes()) {
      return parse_error("element '" + e.name + "' claims " + std::to_string(e.count) +
                         " items but only " + std::to_string(in.remaining_bytes()) + " bytes follow");
    }
    const bool is_vertex = e.name == "vertex";
    if (is_vertex) mesh->positions.reserve(e.count);
    std::vector<int64_t> list;
    for (uint64_t i = 0; i < e.count; ++i) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (const Property& prop : e.properties) {
        double v = 0;
        if (prop.count_type.empty()) {
          SRCODEC_RETURN_IF_ERROR(in.read(prop.type, &v).with_context("element '" + e.name + "' item " + std::to_string(i)));
          if (is_vertex && prop.name.size() == 1 && prop.name[0] >= 'x' && prop.name[0] <= 'z') p[prop.name[0] - 'x'] = v;
          continue;
        }
        double count = 0;
        SRCODEC_RETURN_IF_ERROR(in.read(prop.count_type, &count));
        if (!(count >= 0 && count <= static_cast<double>(in.remaining_bytes())))  // NaN too
          return parse_error("element '" + e.name + "' item " + std::to_string(i) + " has an impossible list length");
        list.resize(static_cast<size_t>(count));
        for (auto& x : list) {
          SRCODEC_RETURN_IF_ERROR(in.read(prop.type, &v));
          // Out of range (or NaN, from a float-typed list): validation names
          // it later. Checked before the conversion, which would be undefined.
          x = v >= -1 && v <= INT32_MAX ? static_cast<int64_t>(v) : INT32_MAX;
        }
        if (e.name == "tristrips") add_strip(list, mesh);
        else if (e.name == "face" && !list.empty()) {
          std::vector<int32_t> face(list.begin(), list.end());
          mesh->add_face(face.data(), static_cast<int32_t>(face.size()));
        }
      }
      if (is_vertex) mesh->positions.push_back(p);
    }
  }
  return ok_status();
}

}  // namespace srcodec
