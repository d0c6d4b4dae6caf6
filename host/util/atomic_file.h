// Output files appear only when complete: each writer writes a temporary file beside the target and renames it into
// place, so an interrupted or failed run never leaves a truncated image that looks like a result.
#pragma once
#include <functional>
#include <string>

namespace rcsplat {

// Throws rcsplat::Error naming path when it is a directory, or when the nearest of its folders that exists is not a
// directory or refuses a new file (probed by creating and removing one, which also catches read-only file systems and
// root's permission overrides): checked before any work, so that a long render never ends unable to save. Folders
// that do not exist yet are made only when the file is written, so a run that fails leaves nothing behind.
void check_writable_destination(const std::string& path);

// Makes path's missing folders, calls write(temporary_path) and on success renames the temporary file to path. write
// returns "" on success or an error message, which is thrown as rcsplat::Error naming path (the temporary file is
// removed).
void write_file_atomically(const std::string& path, const std::function<std::string(const std::string&)>& write);

// Writes text to path atomically, as write_file_atomically does. Throws rcsplat::Error.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace rcsplat
