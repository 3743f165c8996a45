// yaml-cpp 0.7's LoadAll never returns on a stray ',' where a document should start (it emits
// null documents forever without consuming the token; jbeder/yaml-cpp#1040, fixed upstream in
// 2024). So documents are counted by driving the parser ourselves, at most twice, before the one
// document is loaded with YAML::Load, which parses a single document only.
#include "yaml_document.hpp"

#include "yaml_fields.hpp"

#include <yaml-cpp/eventhandler.h>

#include <sstream>

namespace impulse2d {
namespace scene_detail {
namespace {

// Counts nesting only to see whether a document's root is a null that sits on a ','.
class StrayCommaProbe : public YAML::EventHandler {
 public:
  explicit StrayCommaProbe(const std::string& text) : text_(text) {}

  bool found() const { return found_; }
  const YAML::Mark& mark() const { return mark_; }

  void OnDocumentStart(const YAML::Mark&) override { depth_ = 0; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override {
    const bool onComma = mark.pos >= 0 && static_cast<size_t>(mark.pos) < text_.size() &&
                         text_[static_cast<size_t>(mark.pos)] == ',';
    if (depth_ == 0 && onComma && !found_) {
      found_ = true;
      mark_ = mark;
    }
  }
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    ++depth_;
  }
  void OnSequenceEnd() override { --depth_; }
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    ++depth_;
  }
  void OnMapEnd() override { --depth_; }

 private:
  const std::string& text_;
  int depth_ = 0;
  bool found_ = false;
  YAML::Mark mark_;
};

}  // namespace

YAML::Node loadSingleDocument(const std::string& text) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  StrayCommaProbe probe(text);
  int documents = 0;
  while (documents < 2 && parser.HandleNextDocument(probe)) ++documents;
  if (probe.found()) throw YAML::ParserException(probe.mark(), "unexpected ','");
  if (documents > 1) throw SceneError("", "the text holds several YAML documents; a scene is one");
  return YAML::Load(text);
}

}  // namespace scene_detail
}  // namespace impulse2d
