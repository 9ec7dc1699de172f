#pragma once
// The fuzz targets' input: the bytes as a file of a given name in a folder of this process's own.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace dresskit::fuzz {

/// Writes size bytes from data to `name` in /tmp/dresskit-fuzz-<pid>/ and returns its path.
inline std::string write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path folder = "/tmp/dresskit-fuzz-" + std::to_string(::getpid());
  std::filesystem::create_directories(folder);
  const std::string path = (folder / name).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                                 static_cast<std::streamsize>(size));
  return path;
}

}  // namespace dresskit::fuzz
