// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// Outputs of the Lua layer: every file is written through the checked
// writers of core/output_file.hpp (whole files: write_file_atomically; CSV
// rows and log lines: AppendFile), so a full disk is an error naming the
// file, never a silent truncation. CSV fields are quoted here.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/output_file.hpp"

namespace dda::script {

using dda::AppendFile;
using dda::write_file_atomically;

// A CSV field: as it is, or in double quotes (quotes doubled) when it holds a
// comma, a quote or a line break.
std::string csv_field(std::string_view s);
// Splits one CSV line into fields (the inverse of csv_field).
std::vector<std::string> csv_split(std::string_view line);

}  // namespace dda::script
