// File access that never blocks on something that is not a regular file (a named pipe, a device, a socket)
// and checks an output path before the work that produces it.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace wb {

// Reads a whole regular file. The file is opened non-blocking and checked with fstat before any read: a named
// pipe, device, socket or directory is refused instead of waiting for a writer. Files larger than maxBytes
// are refused too. On failure returns nullopt and, when why is given, sets it to a one-line reason.
std::optional<std::string> readRegularFile(const std::filesystem::path& path, std::string* why = nullptr,
                                           uint64_t maxBytes = uint64_t{4} << 30);

// What kind of file is at path, for messages ("a directory", "a named pipe", ...; "missing" when nothing is
// there, "a regular file" for files, "a symbolic link to 'x', which does not exist" for a dangling link).
std::string describeFileKind(const std::filesystem::path& path);

// Checks that a file can be written at path as writeFileAtomically() writes it (common/atomic_file.h):
// creates its missing folders; an existing file is opened for writing without being truncated, and a file is
// created in its folder and removed again (the new content goes there first). Throws std::runtime_error
// naming `what` (the flag, e.g. "--out"), the path and the reason.
void requireWritableFile(const std::filesystem::path& path, const std::string& what);

// Checks that dir is (or can be made, with its parents) a folder where files can be created. Throws
// std::runtime_error naming `what`, the path and the reason. Creates the folder.
void requireWritableDirectory(const std::filesystem::path& dir, const std::string& what);

}  // namespace wb
