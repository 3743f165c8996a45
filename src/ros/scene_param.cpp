// Reading the ~scene parameter (see scene_param.hpp).
#include "scene_param.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace impulse2d {
namespace bridge {
namespace {

void writeString(const std::string& s, std::ostringstream& out) {
  out << '"';
  for (const char c : s) {
    switch (c) {
      case '"':
        out << "\\\"";
        break;
      case '\\':
        out << "\\\\";
        break;
      case '\n':
        out << "\\n";
        break;
      case '\t':
        out << "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned char>(c));
          out << buf;
        } else {
          out << c;
        }
    }
  }
  out << '"';
}

void writeDouble(double v, std::ostringstream& out) {
  if (std::isnan(v)) {
    out << ".nan";
  } else if (std::isinf(v)) {
    out << (v > 0 ? ".inf" : "-.inf");
  } else {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    out << buf;
  }
}

void write(XmlRpc::XmlRpcValue& value, std::ostringstream& out) {
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      out << (static_cast<bool>(value) ? "true" : "false");
      break;
    case XmlRpc::XmlRpcValue::TypeInt:
      out << static_cast<int>(value);
      break;
    case XmlRpc::XmlRpcValue::TypeDouble:
      writeDouble(static_cast<double>(value), out);
      break;
    case XmlRpc::XmlRpcValue::TypeString:
      writeString(static_cast<std::string>(value), out);
      break;
    case XmlRpc::XmlRpcValue::TypeArray: {
      out << '[';
      for (int i = 0; i < value.size(); ++i) {
        if (i > 0) out << ", ";
        write(value[i], out);
      }
      out << ']';
      break;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      out << '{';
      bool first = true;
      for (auto& member : value) {
        if (!first) out << ", ";
        first = false;
        writeString(member.first, out);
        out << ": ";
        write(member.second, out);
      }
      out << '}';
      break;
    }
    default:  // dates, binary and invalid values have no place in a scene
      out << "null";
  }
}

}  // namespace

std::string toYaml(XmlRpc::XmlRpcValue& value) {
  std::ostringstream out;
  write(value, out);
  return out.str();
}

SceneParam readSceneParam(const ros::NodeHandle& nh, const std::string& name, std::string* yaml,
                          std::string* error) {
  XmlRpc::XmlRpcValue value;
  if (!nh.getParam(name, value)) return SceneParam::Missing;
  if (value.getType() == XmlRpc::XmlRpcValue::TypeString) {
    *yaml = static_cast<std::string>(value);
    return SceneParam::Ok;
  }
  if (value.getType() == XmlRpc::XmlRpcValue::TypeStruct) {
    *yaml = toYaml(value);
    return SceneParam::Ok;
  }
  *error = "must be YAML text or a dictionary in the scene schema";
  return SceneParam::Bad;
}

}  // namespace bridge
}  // namespace impulse2d
