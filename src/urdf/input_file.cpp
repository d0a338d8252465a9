// See input_file.hpp.
#include "input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace ragdoll_sim {

namespace {

const char* kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a named pipe";
  if (S_ISSOCK(mode)) return "a socket";
  return "of another kind";
}

std::string limitText() {
  return std::to_string(kMaxInputFileBytes >> 20) + " MiB";
}

// Closes the descriptor on every return path.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

bool readInputFile(const std::string& path, const std::string& what, std::string* text,
                   std::string* error) {
  const std::string name = what + " '" + path + "'";
  const std::string rule = "; only regular files up to " + limitText() + " are read";
  // O_NONBLOCK: opening a FIFO with no writer must not wait for one.
  Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (f.fd < 0) {
    *error = "cannot open " + name + ": " + std::strerror(errno);
    return false;
  }
  // fstat of the opened descriptor, not stat of the path: the file checked is the file read.
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) {
    *error = "cannot stat " + name + ": " + std::strerror(errno);
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    *error = name + " is not a regular file (" + kindOf(st.st_mode) + ")" + rule;
    return false;
  }
  const auto tooLarge = [&](const std::string& size) {
    *error = name + " is too large (" + size + " bytes)" + rule;
    return false;
  };
  const std::string grown = "more than " + std::to_string(kMaxInputFileBytes);
  if (st.st_size < 0 || static_cast<unsigned long long>(st.st_size) > kMaxInputFileBytes)
    return tooLarge(std::to_string(st.st_size));
  // Read at most limit + 1 bytes whatever st_size said: a file that grows meanwhile stays bounded.
  std::string out;
  out.resize(static_cast<size_t>(st.st_size) + 1);
  size_t used = 0;
  for (;;) {
    if (used == out.size()) {
      if (out.size() > kMaxInputFileBytes) return tooLarge(grown);
      out.resize(std::min(out.size() * 2, kMaxInputFileBytes + 1));
    }
    const ssize_t n = ::read(f.fd, &out[used], out.size() - used);
    if (n < 0) {
      if (errno == EINTR) continue;
      *error = "cannot read " + name + ": " + std::strerror(errno);
      return false;
    }
    if (n == 0) break;
    used += static_cast<size_t>(n);
  }
  if (used > kMaxInputFileBytes) return tooLarge(grown);
  out.resize(used);
  *text = std::move(out);
  return true;
}

}  // namespace ragdoll_sim
