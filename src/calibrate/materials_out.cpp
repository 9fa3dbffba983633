#include "calibrate/materials_out.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "calibrate/csv_table.hpp"
#include "calibrate/input_error.hpp"

namespace grainlab::calibrate {
namespace {

struct Pair {
  std::string a, b;
  std::vector<std::pair<std::string, std::string>> keys;  // key, value as TOML text
  std::map<std::string, std::string> comments;            // key -> comment text
};

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  return s;
}

// `s` with every byte outside printable ASCII as \xNN (for a message about a bad name).
std::string printable(const std::string& s) {
  std::string out;
  for (char c : s) {
    const auto b = static_cast<unsigned char>(c);
    out += b >= 0x20 && b < 0x7F ? std::string(1, c) : fmt::format("\\x{:02X}", b);
  }
  return out;
}

// A TOML basic string: double quotes, with backslash, quote and control characters escaped.
std::string toml_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\')
      out += {'\\', c};
    else if (static_cast<unsigned char>(c) < 0x20)
      out += fmt::format("\\u{:04X}", static_cast<unsigned>(c));
    else
      out += c;
  }
  return out + "\"";
}

// A float in TOML: the shortest text that reads back to the same double, always with a
// decimal point or exponent so it stays a float.
std::string toml_float(double x) {
  std::string s = fmt::format("{}", x);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// An existing value as TOML text (scalars written the way this file writes them).
std::string toml_value(const toml::node& node) {
  if (auto d = node.value_exact<double>()) return toml_float(*d);
  if (auto s = node.value_exact<std::string>()) return toml_string(*s);
  std::ostringstream out;
  node.visit([&](const auto& n) { out << n; });
  return out.str();
}

bool same_pair(const Pair& p, const std::string& a, const std::string& b) {
  return (p.a == a && p.b == b) || (p.a == b && p.b == a);
}

// The "# key: text" comments inside each [[pair]] block of the file, block by block.
std::vector<std::map<std::string, std::string>> read_comments(const std::string& text) {
  std::vector<std::map<std::string, std::string>> blocks;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    const std::string_view l = std::string_view(line).substr(first);
    if (l.starts_with("[[pair]]")) {
      blocks.emplace_back();
      continue;
    }
    if (blocks.empty() || !l.starts_with("#")) continue;
    const auto colon = l.find(':');
    if (colon == std::string_view::npos) continue;
    std::string_view key = l.substr(1, colon - 1);
    while (!key.empty() && key.front() == ' ') key.remove_prefix(1);
    if (key.empty() || key.find(' ') != std::string_view::npos) continue;
    std::string_view rest = l.substr(colon + 1);
    while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
    blocks.back()[std::string(key)] = std::string(rest);
  }
  return blocks;
}

std::vector<Pair> read_pairs(const std::string& text, const std::string& file_name) {
  std::vector<Pair> pairs;
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) return pairs;
  toml::table root;
  try {
    root = toml::parse(text, file_name);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{} line {}: not a valid TOML file: {}", file_name,
                                 e.source().begin.line, e.description()));
  }
  for (const auto& [key, node] : root)
    if (key.str() != "pair")
      throw InputError(
          fmt::format("{}: has '{}' besides the [[pair]] tables; --materials-out "
                      "only rewrites a file of [[pair]] entries (use a new file and "
                      "copy the entries into your scene)",
                      file_name, key.str()));
  const auto comments = read_comments(text);
  const toml::array* array = root["pair"].as_array();
  if (!array && root.contains("pair"))
    throw InputError(fmt::format("{}: 'pair' must be an array of tables ([[pair]])", file_name));
  if (!array) return pairs;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::table* t = (*array)[i].as_table();
    const toml::array* mats = t ? (*t)["materials"].as_array() : nullptr;
    if (!mats || mats->size() != 2 || !(*mats)[0].is_string() || !(*mats)[1].is_string()) {
      const auto line = t ? t->source().begin.line : 0;
      throw InputError(
          fmt::format("{} line {}: a [[pair]] needs materials = [\"a\", \"b\"]", file_name, line));
    }
    Pair p;
    p.a = *(*mats)[0].value<std::string>();
    p.b = *(*mats)[1].value<std::string>();
    for (const auto& [k, v] : *t) {
      if (k.str() == "materials") continue;
      p.keys.emplace_back(std::string(k.str()), toml_value(v));
    }
    if (i < comments.size())
      for (const auto& [k, c] : comments[i])
        if (std::any_of(p.keys.begin(), p.keys.end(),
                        [&](const auto& kv) { return kv.first == k; }))
          p.comments[k] = c;
    pairs.push_back(std::move(p));
  }
  return pairs;
}

int key_rank(const std::string& key) {
  if (key == "restitution") return 0;
  if (key == "friction") return 1;
  return 2;
}

}  // namespace

std::string merge_materials_toml(const std::string& existing, const std::string& file_name,
                                 const std::vector<PairUpdate>& updates) {
  std::vector<Pair> pairs = read_pairs(existing, file_name);
  for (const PairUpdate& u : updates)
    for (const std::string* name : {&u.material_a, &u.material_b})
      if (!valid_utf8(*name) || name->empty())
        throw InputError(fmt::format(
            "{}: the material name '{}' is {}; names in [[pair]] entries must be UTF-8 text "
            "(--bead-material, --material, or the data's material column; --rename FROM=TO)",
            file_name, printable(*name), name->empty() ? "empty" : "not valid UTF-8"));
  for (const PairUpdate& u : updates) {
    auto it = std::find_if(pairs.begin(), pairs.end(),
                           [&](const Pair& p) { return same_pair(p, u.material_a, u.material_b); });
    if (it == pairs.end()) {
      pairs.push_back({u.material_a, u.material_b, {}, {}});
      it = std::prev(pairs.end());
    }
    for (const PairValue& v : u.values) {
      const std::string text = fmt::format("{:.4f}", v.value);
      auto k = std::find_if(it->keys.begin(), it->keys.end(),
                            [&](const auto& kv) { return kv.first == v.key; });
      if (k == it->keys.end())
        it->keys.emplace_back(v.key, text);
      else
        k->second = text;
      it->comments[v.key] = one_line(v.provenance);
    }
  }
  std::string out =
      "# Material pairs calibrated from laboratory measurements by `grainlab calibrate`.\n"
      "# Running `grainlab calibrate ... --materials-out` on this file again updates the values\n"
      "# it computes and keeps everything else. Copy the entries into a scene file.\n";
  for (Pair& p : pairs) {
    std::stable_sort(p.keys.begin(), p.keys.end(), [](const auto& x, const auto& y) {
      return key_rank(x.first) < key_rank(y.first);
    });
    out += fmt::format("\n[[pair]]\nmaterials = [{}, {}]\n", toml_string(p.a), toml_string(p.b));
    for (const auto& [key, value] : p.keys) {
      if (auto c = p.comments.find(key); c != p.comments.end())
        out += fmt::format("# {}: {}\n", key, c->second);
      out += fmt::format("{} = {}\n", key, value);
    }
  }
  // The result must read back (guards the merge against a malformed value).
  try {
    (void)toml::parse(out, file_name);
  } catch (const toml::parse_error& e) {
    throw std::runtime_error(
        fmt::format("internal error: merged {} is not valid TOML: {}", file_name, e.description()));
  }
  return out;
}

void write_file_atomically(const std::string& path, const std::string& content) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path tmp =
      target.parent_path() / fmt::format(".{}.tmp.{}", target.filename().string(), ::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw std::runtime_error(
          fmt::format("{}: cannot write (temporary file {})", path, tmp.string()));
    out << content;
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw std::runtime_error(fmt::format("{}: writing failed", path));
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error(fmt::format("{}: cannot replace the file: {}", path, ec.message()));
  }
}

void write_materials_toml(const std::string& path, const std::vector<PairUpdate>& updates) {
  std::string existing;
  if (std::filesystem::exists(path)) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(fmt::format("{}: cannot read the existing file", path));
    std::ostringstream buffer;
    buffer << in.rdbuf();
    existing = buffer.str();
  }
  write_file_atomically(path, merge_materials_toml(existing, path, updates));
}

}  // namespace grainlab::calibrate
