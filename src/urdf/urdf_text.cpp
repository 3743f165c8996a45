// Parsing URDF text with urdfdom, keeping its log messages for the error we return.
#include "urdf_text.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <exception>
#include <mutex>

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

}  // namespace urdf_detail
}  // namespace impulse2d
