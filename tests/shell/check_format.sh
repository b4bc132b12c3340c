#!/usr/bin/env bash
# Every C++ file of src/, tests/ and bench/ is as .clang-format lays it out (clang-format 14, as
# Debian 12 ships it: another version may lay out the same code otherwise, so this test runs
# only with the version the style was applied with).
#   tests/shell/check_format.sh CLANG_FORMAT SOURCE_DIR
set -euo pipefail
clang_format=$1
cd "$2"
version=$("$clang_format" --version)
case "$version" in
  *" version 14."*) ;;
  *) echo "check_format: $version is not clang-format 14; skipped"; exit 77 ;;
esac
find src tests bench -name '*.[ch]pp' -print0 | sort -z | xargs -0 "$clang_format" --dry-run --Werror
