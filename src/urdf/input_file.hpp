// Reading a whole input file (URDF, package.xml, mesh) without trusting the path: only a
// regular file of at most kMaxInputFileBytes is read, so a device, a pipe or a huge file is
// refused at once instead of filling memory or blocking the caller.
#pragma once

#include <string>

#include "ragdoll_sim/urdf_loader.hpp"  // kMaxInputFileBytes

namespace ragdoll_sim {

// The whole of the regular file at `path` into *text. false with *error ("<what> '<path>' is
// not a regular file (a named pipe); only regular files up to 64 MiB are read") when it cannot
// be opened, is not a regular file, or is (or grows while being read) above the limit.
bool readInputFile(const std::string& path, const std::string& what, std::string* text,
                   std::string* error);

}  // namespace ragdoll_sim
