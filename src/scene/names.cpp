// Name rules of scenes; they match World::validate(BodyDef) so a name is refused in one wording
// whether it comes from a scene file or a ROS service.
#include "names.hpp"

#include <impulse2d/limits.hpp>

namespace impulse2d {
namespace scene_detail {
namespace {

// Quoted user text is cut here: a message is read by a person, often on one terminal line.
constexpr size_t kMaxQuotedLength = 64;

bool frameNameChar(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '/' || c == '-';
}

}  // namespace

std::string checkName(const std::string& name) {
  if (name.empty()) return "must not be empty";
  if (name.size() > kMaxNameLength) {
    return "must be at most " + std::to_string(kMaxNameLength) + " characters";
  }
  for (char c : name) {
    if (!frameNameChar(c)) return "may only contain letters, digits, '_', '-' and '/'";
  }
  if (name[0] == '/') return "must not start with '/'";
  return "";
}

std::string checkTopic(const std::string& name) {
  if (name.empty()) return "must not be empty";
  if (name.size() > kMaxNameLength) {
    return "must be at most " + std::to_string(kMaxNameLength) + " characters";
  }
  const char* rule =
      "must be a ROS topic name: segments of letters, digits and '_' starting with a "
      "letter, separated by '/' (a leading '/' makes it absolute)";
  bool segmentStart = true;
  for (size_t i = name[0] == '/' ? 1 : 0; i < name.size(); ++i) {
    const char c = name[i];
    const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z');
    const bool digit = c >= '0' && c <= '9';
    if (c == '/') {
      if (segmentStart) return rule;  // "//" or a trailing '/'
      segmentStart = true;
      continue;
    }
    if (segmentStart ? !letter : !(letter || digit || c == '_')) return rule;
    segmentStart = false;
  }
  if (segmentStart) return rule;  // "/" alone or a trailing '/'
  return "";
}

std::string printable(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (out.size() == kMaxQuotedLength) return out + "...";
    const unsigned char u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u == 0x7f) ? '?' : c;
  }
  return out;
}

std::string quoted(const std::string& text) { return "'" + printable(text) + "'"; }

}  // namespace scene_detail
}  // namespace impulse2d
