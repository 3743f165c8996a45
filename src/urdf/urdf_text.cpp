// Parsing URDF text with urdfdom, keeping its log messages for the error we return.
#include "urdf_text.hpp"

#include "link_geometry.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <tinyxml.h>

#include <algorithm>
#include <exception>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace impulse2d {
namespace urdf_detail {
namespace {

// Far above any real robot description; keeps a hostile request from costing much.
constexpr size_t kMaxUrdfBytes = 8u << 20;

class CapturingHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) lastError = text;
  }
  std::string lastError;
};

// console_bridge's handler is process-wide: parses take turns, and whatever another thread logs
// through console_bridge during one parse is not printed (a short window, and only its logs).
std::mutex& handlerMutex() {
  static std::mutex mutex;
  return mutex;
}

// TinyXML parses nested elements recursively: a hostile document nested a million deep would
// overflow the stack. URDF nests about five deep.
constexpr int kMaxNesting = 100;

// An upper bound on the element nesting (a '<' inside a comment or CDATA section may count).
int nestingDepth(const std::string& xml) {
  int depth = 0, deepest = 0;
  for (size_t i = 0; i + 1 < xml.size(); ++i) {
    if (xml[i] != '<') continue;
    const char next = xml[i + 1];
    if (next == '/') {
      --depth;
    } else if (next != '!' && next != '?') {
      deepest = std::max(deepest, ++depth);
      const size_t close = xml.find('>', i);
      if (close != std::string::npos && close > i && xml[close - 1] == '/') --depth;
    }
  }
  return deepest;
}

std::string quoted(const char* text) { return quotedName(text ? text : ""); }

// The offset of the first byte that does not start a well-formed UTF-8 sequence, or npos.
// TinyXML (which urdfdom parses with too) takes a lead byte's word for how many bytes follow:
// a text ending in a lead byte made it read past the end of the buffer (the URDF fuzzer,
// 2026-11-26).
size_t invalidUtf8At(const std::string& text) {
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const size_t follow = c < 0x80                   ? 0
                          : (c >= 0xC2 && c <= 0xDF) ? 1
                          : (c >= 0xE0 && c <= 0xEF) ? 2
                          : (c >= 0xF0 && c <= 0xF4) ? 3
                                                     : 4;  // never a lead byte
    if (follow == 4 || text.size() - i <= follow) return i;
    for (size_t k = 1; k <= follow; ++k) {
      const unsigned char next = static_cast<unsigned char>(text[i + k]);
      if (next < 0x80 || next > 0xBF) return i;
    }
    i += follow + 1;
  }
  return std::string::npos;
}

// urdfdom links a joint's child into its parent's child list before it looks for loops, so a
// loop of joints becomes a shared_ptr cycle that leaks even when urdfdom refuses the model.
// Refused here first. Bad XML is left to urdfdom, which words it.
std::string findJointLoop(const std::string& xml) {
  TiXmlDocument document;
  document.Parse(xml.c_str());
  const TiXmlElement* robot = document.Error() ? nullptr : document.FirstChildElement("robot");
  if (robot == nullptr) return "";
  std::map<std::string, std::string> parentOf, jointOf;  // child link -> parent link, joint
  for (const TiXmlElement* joint = robot->FirstChildElement("joint"); joint != nullptr;
       joint = joint->NextSiblingElement("joint")) {
    const TiXmlElement* parent = joint->FirstChildElement("parent");
    const TiXmlElement* child = joint->FirstChildElement("child");
    const char* parentLink = parent ? parent->Attribute("link") : nullptr;
    const char* childLink = child ? child->Attribute("link") : nullptr;
    if (parentLink == nullptr || childLink == nullptr) continue;  // urdfdom refuses those
    if (parentOf.count(childLink)) {
      return "link " + quoted(childLink) + " is the child of two joints, " +
             quoted(jointOf[childLink].c_str()) + " and " + quoted(joint->Attribute("name"));
    }
    parentOf[childLink] = parentLink;
    jointOf[childLink] = joint->Attribute("name") ? joint->Attribute("name") : "";
  }
  // Each link has at most one parent, so following parents either ends or runs in a circle.
  std::map<std::string, int> state;  // 1: on the current path, 2: known to end
  for (const auto& start : parentOf) {
    std::vector<std::string> path;
    std::string at = start.first;
    while (state[at] == 0) {
      state[at] = 1;
      path.push_back(at);
      const auto up = parentOf.find(at);
      if (up == parentOf.end()) break;
      at = up->second;
    }
    if (state[at] == 1 && parentOf.count(at)) {
      return "joint " + quoted(jointOf[at].c_str()) + ": the joints form a loop through link " +
             quoted(at.c_str());
    }
    for (const std::string& link : path) state[link] = 2;
  }
  return "";
}

}  // namespace

urdf::ModelInterfaceSharedPtr parseUrdfText(const std::string& xml, std::string* error) {
  if (xml.empty()) {
    *error = "urdf_xml: empty";
    return nullptr;
  }
  if (xml.size() > kMaxUrdfBytes) {
    *error = "urdf_xml: larger than " + std::to_string(kMaxUrdfBytes) + " bytes";
    return nullptr;
  }
  if (xml.find('\0') != std::string::npos) {
    *error = "urdf_xml: contains a NUL byte";
    return nullptr;
  }
  if (const size_t at = invalidUtf8At(xml); at != std::string::npos) {
    *error =
        "urdf_xml: not valid UTF-8 at byte " + std::to_string(at) + " (URDF text must be UTF-8)";
    return nullptr;
  }
  if (nestingDepth(xml) > kMaxNesting) {
    *error = "urdf_xml: elements nested deeper than " + std::to_string(kMaxNesting);
    return nullptr;
  }
  const std::string loop = findJointLoop(xml);
  if (!loop.empty()) {
    *error = "urdf_xml: " + loop;
    return nullptr;
  }
  CapturingHandler capture;
  urdf::ModelInterfaceSharedPtr model;
  {
    std::lock_guard<std::mutex> lock(handlerMutex());
    console_bridge::OutputHandler* previous = console_bridge::getOutputHandler();
    console_bridge::useOutputHandler(&capture);
    try {
      model = urdf::parseURDF(xml);
    } catch (const std::exception& e) {
      model.reset();
      capture.lastError = e.what();
    }
    console_bridge::useOutputHandler(previous);
  }
  if (!model) {
    std::string why = capture.lastError;
    while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
    *error = "urdf_xml: not a valid URDF: " + (why.empty() ? std::string("bad XML") : why);
  }
  return model;
}

ModelReleaser::~ModelReleaser() {
  if (!model_) return;
  for (auto& entry : model_->links_) {
    if (!entry.second) continue;
    entry.second->child_links.clear();
    entry.second->child_joints.clear();
  }
}

}  // namespace urdf_detail
}  // namespace impulse2d
