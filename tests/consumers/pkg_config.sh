#!/usr/bin/env bash
# Builds and runs the consumer with nothing but pkg-config and the compiler.
# usage: pkg_config.sh CXX PREFIX SOURCE WORKDIR
set -euo pipefail
cxx=$1 prefix=$2 source=$3 work=$4
mkdir -p "$work"
flags=$(PKG_CONFIG_PATH="$prefix/share/pkgconfig" pkg-config --cflags shade)
echo "pkg-config --cflags shade: $flags"
# shellcheck disable=SC2086 # the flags are meant to split into words
"$cxx" $flags "$source" -o "$work/consumer"
"$work/consumer"
