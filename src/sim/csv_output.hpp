// The CSV files of impulse2d_sim: body states and contact points, at full double precision.
#pragma once

#include <impulse2d/world.hpp>

#include <cstdint>
#include <cstdio>
#include <string>

namespace impulse2d {
namespace sim {

/// One output file. Writes are checked once, at close(), where the first error is reported.
class CsvFile {
 public:
  CsvFile() = default;
  ~CsvFile();
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;

  /// Creates or truncates `path` and writes `header`. False with a reason when it cannot.
  bool open(const std::string& path, const char* header, std::string* error);
  bool isOpen() const { return file_ != nullptr; }
  /// Flushes and closes; false with a reason when anything could not be written.
  bool close(std::string* error);

  /// step,time,body,x,y,angle,vx,vy,omega for each dynamic or kinematic body.
  void writeBodies(const World& world, uint64_t step);
  /// step,body_a,body_b,x,y,nx,ny,separation,normal_impulse,tangent_impulse for each contact.
  void writeContacts(const World& world, uint64_t step);

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
};

extern const char* const kBodyHeader;
extern const char* const kContactHeader;

}  // namespace sim
}  // namespace impulse2d
