#pragma once
// Whole-file outputs (results, sweep tables, VTU and PVD files): written
// into NAME.part, every write checked, then renamed over NAME, so a reader
// never sees half a file and a full disk is an error naming the file, never
// a silent truncation.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace dda::script {

// Throws dda::Error "cannot write 'PATH': cause" on any failure (the old
// file, if any, is left as it was).
void write_file_atomically(const std::filesystem::path& path, std::string_view text);

// A CSV field: as it is, or in double quotes (quotes doubled) when it holds a
// comma, a quote or a line break.
std::string csv_field(std::string_view s);
// Splits one CSV line into fields (the inverse of csv_field).
std::vector<std::string> csv_split(std::string_view line);

}  // namespace dda::script
