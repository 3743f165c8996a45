// CSV rows with %.17g, which round-trips every double, so a CSV can be compared bit for bit.
#include "csv_output.hpp"

#include <cerrno>
#include <cinttypes>
#include <cstring>

namespace impulse2d {
namespace sim {

const char* const kBodyHeader = "step,time,body,x,y,angle,vx,vy,omega";
const char* const kContactHeader =
    "step,body_a,body_b,x,y,nx,ny,separation,normal_impulse,tangent_impulse";

CsvFile::~CsvFile() {
  if (file_ != nullptr) std::fclose(file_);
}

bool CsvFile::open(const std::string& path, const char* header, std::string* error) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) {
    *error = "cannot write '" + path + "': " + std::strerror(errno);
    return false;
  }
  path_ = path;
  std::fprintf(file_, "%s\n", header);
  return true;
}

bool CsvFile::close(std::string* error) {
  if (file_ == nullptr) return true;
  const bool failed = std::fflush(file_) != 0 || std::ferror(file_) != 0;
  const int savedErrno = errno;
  const bool closeFailed = std::fclose(file_) != 0;
  file_ = nullptr;
  if (failed || closeFailed) {
    *error = "cannot write '" + path_ + "': " + std::strerror(failed ? savedErrno : errno);
    return false;
  }
  return true;
}

void CsvFile::writeBodies(const World& world, uint64_t step) {
  const double time = world.time();
  for (const BodyId id : world.bodies()) {
    const Body& b = world.body(id);
    if (b.type == BodyType::Static) continue;
    std::fprintf(file_, "%" PRIu64 ",%.17g,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", step, time,
                 b.name.c_str(), b.xf.p.x(), b.xf.p.y(), b.angle, b.linearVelocity.x(),
                 b.linearVelocity.y(), b.angularVelocity);
  }
}

void CsvFile::writeContacts(const World& world, uint64_t step) {
  for (const ContactInfo& c : world.contacts()) {
    std::fprintf(file_, "%" PRIu64 ",%s,%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", step,
                 world.body(c.bodyA).name.c_str(), world.body(c.bodyB).name.c_str(), c.point.x(),
                 c.point.y(), c.normal.x(), c.normal.y(), c.separation, c.normalImpulse,
                 c.tangentImpulse);
  }
}

}  // namespace sim
}  // namespace impulse2d
