// A flat-or-nested JSON object writer for the CLI's --json output.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace srcodec {

class JsonWriter {
 public:
  JsonWriter() { out_ = "{"; }

  JsonWriter& field(const std::string& key, const std::string& value) { return raw(key, quote(value)); }
  JsonWriter& field(const std::string& key, const char* value) { return raw(key, quote(value)); }
  JsonWriter& field(const std::string& key, bool value) { return raw(key, value ? "true" : "false"); }
  JsonWriter& field(const std::string& key, size_t value) { return raw(key, std::to_string(value)); }
  JsonWriter& field(const std::string& key, long value) { return raw(key, std::to_string(value)); }
  JsonWriter& field(const std::string& key, int value) { return raw(key, std::to_string(value)); }
  JsonWriter& field(const std::string& key, double value) {
    if (!std::isfinite(value)) return raw(key, value > 0 ? "1e308" : (value < 0 ? "-1e308" : "null"));
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.10g", value);
    return raw(key, buffer);
  }
  JsonWriter& null_field(const std::string& key) { return raw(key, "null"); }
  JsonWriter& object(const std::string& key, const JsonWriter& inner) { return raw(key, inner.str()); }
  JsonWriter& array(const std::string& key, const std::vector<JsonWriter>& items) {
    std::string a = "[";
    for (size_t i = 0; i < items.size(); ++i) a += (i ? ", " : "") + items[i].str();
    return raw(key, a + "]");
  }

  std::string str() const { return out_ + "}"; }

 private:
  JsonWriter& raw(const std::string& key, const std::string& value) {
    if (out_.size() > 1) out_ += ", ";
    out_ += quote(key) + ": " + value;
    return *this;
  }
  static std::string quote(const std::string& s) {
    std::string q = "\"";
    for (unsigned char c : s) {
      if (c == '"' || c == '\\') {
        q += '\\';
        q += static_cast<char>(c);
      } else if (c < 0x20) {
        char buffer[8];
        std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
        q += buffer;
      } else {
        q += static_cast<char>(c);
      }
    }
    return q + "\"";
  }

  std::string out_;
};

}  // namespace srcodec
