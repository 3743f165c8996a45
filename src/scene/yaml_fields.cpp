// Typed reads of scene YAML maps. Numbers are parsed here rather than by yaml-cpp's stream
// conversions, which read "010" as octal and accept trailing junk in some locales.
#include "yaml_fields.hpp"

#include "names.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <limits>

namespace impulse2d {
namespace scene_detail {
namespace {

constexpr int kMaxMergedMaps = 64;

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// A typo is reported with the closest known key; otherwise the known keys are listed.
std::string unknownKeyMessage(const std::string& key, std::initializer_list<const char*> allowed) {
  std::string best;
  size_t bestDistance = std::numeric_limits<size_t>::max();
  std::string all;
  for (const char* candidate : allowed) {
    const size_t d = editDistance(key, candidate);
    if (d < bestDistance) {
      bestDistance = d;
      best = candidate;
    }
    all += all.empty() ? "" : ", ";
    all += candidate;
  }
  if (bestDistance <= std::max<size_t>(2, key.size() / 3)) {
    return "unknown key (did you mean '" + best + "'?)";
  }
  return "unknown key (expected one of: " + all + ")";
}

bool isSpecial(const std::string& s, std::initializer_list<const char*> spellings) {
  return std::find(spellings.begin(), spellings.end(), s) != spellings.end();
}

bool toInteger(const YAML::Node& node, int* out) {
  if (!node.IsScalar()) return false;
  const std::string& s = node.Scalar();
  const size_t digits = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
  if (s.size() == digits || s.find_first_not_of("0123456789", digits) != std::string::npos) {
    return false;
  }
  errno = 0;
  const long long v = std::strtoll(s.c_str(), nullptr, 10);
  if (errno == ERANGE || v < INT_MIN || v > INT_MAX) return false;
  *out = static_cast<int>(v);
  return true;
}

// Decimal or 0x-prefixed hexadecimal, 0 .. 2^64 - 1 (collision filter bits).
bool toBits(const YAML::Node& node, uint64_t* out) {
  if (!node.IsScalar()) return false;
  const std::string& s = node.Scalar();
  const bool hex = s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
  const size_t start = hex ? 2 : 0;
  if (s.size() == start || s.find_first_not_of(hex ? "0123456789abcdefABCDEF" : "0123456789",
                                               start) != std::string::npos) {
    return false;
  }
  errno = 0;
  const unsigned long long v = std::strtoull(s.c_str() + start, nullptr, hex ? 16 : 10);
  if (errno == ERANGE) return false;
  *out = static_cast<uint64_t>(v);
  return true;
}

}  // namespace

bool toNumber(const YAML::Node& node, double* out) {
  if (!node.IsScalar()) return false;
  const std::string& s = node.Scalar();
  if (isSpecial(s, {".inf", ".Inf", ".INF", "+.inf", "+.Inf", "+.INF"})) {
    *out = std::numeric_limits<double>::infinity();
    return true;
  }
  if (isSpecial(s, {"-.inf", "-.Inf", "-.INF"})) {
    *out = -std::numeric_limits<double>::infinity();
    return true;
  }
  if (isSpecial(s, {".nan", ".NaN", ".NAN"})) {
    *out = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  // strtod alone would also take "inf", "nan" and hexadecimal, which YAML does not call numbers.
  if (s.empty() || s.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
  const char* begin = s.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  if (end == begin || *end != '\0') return false;
  // Out of range becomes +-inf (or 0), which the value checks then refuse as not finite.
  *out = v;
  return true;
}

Fields::Fields(const YAML::Node& node, const char* what,
               std::initializer_list<const char*> allowed) {
  if (node.IsNull()) return;
  if (!node.IsMap()) throw SceneError("", std::string("must be a map describing ") + what);
  int mergeBudget = kMaxMergedMaps;
  add(node, allowed, false, &mergeBudget);
}

// YAML merge keys ("<<: *defaults", or a list of them) as PyYAML and so rosparam read them: the
// map's own keys win, then earlier merged maps over later ones.
void Fields::add(const YAML::Node& map, std::initializer_list<const char*> allowed, bool merged,
                 int* mergeBudget) {
  std::vector<YAML::Node> merges;
  for (const auto& entry : map) {
    if (!entry.first.IsScalar()) throw SceneError("", "keys must be plain names");
    const std::string key = entry.first.Scalar();
    if (key == "<<") {
      merges.push_back(entry.second);
      continue;
    }
    if (std::find_if(allowed.begin(), allowed.end(), [&](const char* k) { return key == k; }) ==
        allowed.end()) {
      throw SceneError(printable(key), unknownKeyMessage(key, allowed));
    }
    if (find(key.c_str()) != nullptr) {
      if (merged) continue;
      throw SceneError(printable(key), "given twice");
    }
    entries_.emplace_back(key, entry.second);
  }
  for (const YAML::Node& source : merges) {
    const bool list = source.IsSequence();
    if (!source.IsMap() && !list) throw SceneError("<<", "must be a map or a list of maps");
    for (size_t i = 0; i < (list ? source.size() : 1); ++i) {
      const YAML::Node item = list ? source[i] : source;
      if (!item.IsMap()) throw SceneError("<<", "must be a map or a list of maps");
      // Aliases can make nested merges grow exponentially; a real scene needs a handful.
      if (--*mergeBudget < 0) throw SceneError("<<", "too many merged maps");
      add(item, allowed, true, mergeBudget);
    }
  }
}

const YAML::Node* Fields::find(const char* key) const {
  for (const auto& entry : entries_) {
    if (entry.first == key) return &entry.second;
  }
  return nullptr;
}

const YAML::Node& Fields::node(const char* key) const {
  const YAML::Node* n = find(key);
  if (n == nullptr) throw SceneError(key, "must be given");
  return *n;
}

double Fields::number(const char* key, double fallback) const {
  const YAML::Node* n = find(key);
  if (n == nullptr) return fallback;
  double v = 0.0;
  if (!toNumber(*n, &v)) throw SceneError(key, "must be a number");
  return v;
}

int Fields::integer(const char* key, int fallback) const {
  const YAML::Node* n = find(key);
  if (n == nullptr) return fallback;
  int v = 0;
  if (!toInteger(*n, &v)) throw SceneError(key, "must be an integer");
  return v;
}

uint64_t Fields::bits(const char* key, uint64_t fallback) const {
  const YAML::Node* n = find(key);
  if (n == nullptr) return fallback;
  uint64_t v = 0;
  if (!toBits(*n, &v)) {
    throw SceneError(key, "must be an unsigned integer below 2^64 (decimal or 0x hexadecimal)");
  }
  return v;
}

bool Fields::boolean(const char* key, bool fallback) const {
  const YAML::Node* n = find(key);
  if (n == nullptr) return fallback;
  bool v = false;
  if (!n->IsScalar() || !YAML::convert<bool>::decode(*n, v)) {
    throw SceneError(key, "must be true or false");
  }
  return v;
}

std::string Fields::string(const char* key, const std::string& fallback) const {
  const YAML::Node* n = find(key);
  if (n == nullptr) return fallback;
  if (!n->IsScalar()) throw SceneError(key, "must be a string");
  return n->Scalar();
}

std::string Fields::name(const char* key) const {
  if (!has(key)) throw SceneError(key, "must be given");
  const std::string value = string(key, "");
  const std::string why = checkName(value);
  if (!why.empty()) throw SceneError(key, why);
  return value;
}

namespace {

bool toVec2(const YAML::Node& node, Vec2* out) {
  if (!node.IsSequence() || node.size() != 2) return false;
  double x = 0.0, y = 0.0;
  if (!toNumber(node[0], &x) || !toNumber(node[1], &y)) return false;
  *out = Vec2(x, y);
  return true;
}

}  // namespace

Vec2 Fields::vec2(const char* key, const Vec2& fallback) const {
  const YAML::Node* n = find(key);
  if (n == nullptr) return fallback;
  Vec2 v;
  if (!toVec2(*n, &v)) throw SceneError(key, "must be a list of two numbers");
  return v;
}

Eigen::Vector3d Fields::vec3(const char* key, const Eigen::Vector3d& fallback) const {
  const YAML::Node* n = find(key);
  if (n == nullptr) return fallback;
  Eigen::Vector3d v;
  if (!n->IsSequence() || n->size() != 3 || !toNumber((*n)[0], &v.x()) ||
      !toNumber((*n)[1], &v.y()) || !toNumber((*n)[2], &v.z())) {
    throw SceneError(key, "must be a list of three numbers");
  }
  return v;
}

std::vector<Vec2> Fields::points(const char* key) const {
  const YAML::Node& n = node(key);
  const char* shape = "must be a list of [x, y] points";
  if (!n.IsSequence()) throw SceneError(key, shape);
  std::vector<Vec2> out;
  for (const YAML::Node& item : n) {
    Vec2 p;
    if (!toVec2(item, &p)) throw SceneError(key, shape);
    out.push_back(p);
  }
  return out;
}

}  // namespace scene_detail
}  // namespace impulse2d
