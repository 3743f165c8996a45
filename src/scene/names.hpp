// Names in scenes: which are acceptable, and how to quote user text inside a one-line message.
#pragma once

#include <string>

namespace impulse2d {
namespace scene_detail {

/// Empty when `name` can name a body, joint or frame: non-empty, at most 256 characters of
/// [A-Za-z0-9_/-], not starting with '/'. Otherwise the reason, e.g. "must not be empty".
std::string checkName(const std::string& name);

/// Empty when `name` can name a ROS topic: relative (under the node's private namespace) or
/// absolute (a leading '/'), segments of letters, digits and '_' that start with a letter, at
/// most 256 characters. Otherwise the reason.
std::string checkTopic(const std::string& name);

/// `text` shortened and with control characters replaced, so an error stays on one line.
std::string printable(const std::string& text);

/// printable(text) in single quotes.
std::string quoted(const std::string& text);

}  // namespace scene_detail
}  // namespace impulse2d
