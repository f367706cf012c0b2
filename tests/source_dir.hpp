// SPDX-License-Identifier: GPL-3.0-or-later
// SPDX-FileCopyrightText: 2026 The dda maintainers
#pragma once
// The repository's root, for the tests that read files from it (data/,
// scripts/). CMake writes it into one generated source (source_dir.cpp.in),
// not onto every test file's compile command, so the commands are the same
// in every clone and ccache serves a fresh clone from its cache.
const char* dda_test_source_dir();
#define DDA_SOURCE_DIR dda_test_source_dir()
