// Reading a rig file: the path is checked before a byte is read, so that /dev/zero, a FIFO or a
// huge file cost nothing (issue 17).
#include <filesystem>
#include <fstream>
#include <system_error>

#include "yaml/rig_loader.h"
#include "yaml/utf8.h"

namespace metrosync {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw RigError(printable(path) + ": " + why);
}

std::string kindOf(fs::file_type t) {
  switch (t) {
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::block:
    case fs::file_type::character:
      return "a device";
    case fs::file_type::fifo:
      return "a FIFO (named pipe)";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}

}  // namespace

std::string readRigFile(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st))
    refuse(path, "cannot open the rig file" + (ec ? " (" + ec.message() + ")" : std::string()));
  if (!fs::is_regular_file(st))
    refuse(path, "is " + kindOf(st.type()) + ", not a rig file (a rig is a regular YAML file)");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) refuse(path, "cannot read the rig file (" + ec.message() + ")");
  const std::string limit = std::to_string(kMaxRigFileBytes >> 20) + " MiB";
  if (size > kMaxRigFileBytes)
    refuse(path, "is " + std::to_string(size) + " bytes, above the " + limit +
                     " limit for a rig file (docs/rig-limits.md)");

  std::ifstream in(path, std::ios::binary);
  if (!in) refuse(path, "cannot open the rig file");
  // one byte more than measured: a file that grew since is refused rather than cut
  std::string text(static_cast<std::size_t>(size) + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) refuse(path, "cannot read the rig file");
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > size) refuse(path, "changed while being read");
  return text;
}

}  // namespace metrosync
