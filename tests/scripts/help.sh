#!/bin/sh
# Every script under script/ answers --help and -h with its usage (naming the script), exit
# status 0, in under a second, and builds and installs nothing. Each script runs from a
# copy of script/ in an empty directory, with the tools a build or an install would call
# (cmake, ctest, make, compilers, apt-get, sudo, dpkg-query, git, valgrind) replaced by
# stubs that fail loudly; afterwards that directory must hold nothing but the copy.
#
#   sh help.sh SCRIPT_DIR
set -eu
src=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/repo/script" "$work/bin"
cp "$src"/* "$work/repo/script/"
for tool in cmake ctest make g++ c++ clang++ apt-get apt sudo dpkg-query git valgrind; do
  printf '#!/bin/sh\necho "stub: %s was called" >&2\nexit 99\n' "$tool" > "$work/bin/$tool"
  chmod +x "$work/bin/$tool"
done
failed=0
count=0
for script in "$work"/repo/script/*; do
  name=$(basename "$script")
  for flag in --help -h; do
    count=$((count + 1))
    start=$(date +%s%N)
    if ! out=$(PATH="$work/bin:$PATH" "$script" "$flag" 2>&1); then
      echo "FAIL: script/$name $flag exited with a non-zero status:"; echo "$out"; failed=$((failed + 1)); continue
    fi
    elapsed_ms=$(( ($(date +%s%N) - start) / 1000000 ))
    if [ "$elapsed_ms" -ge 1000 ]; then
      echo "FAIL: script/$name $flag took $elapsed_ms ms (limit 1000)"; failed=$((failed + 1))
    fi
    case "$out" in
      *"script/$name"*) ;;
      *) echo "FAIL: script/$name $flag printed no usage naming the script:"; echo "$out"; failed=$((failed + 1)) ;;
    esac
  done
done
leftover=$(cd "$work/repo" && find . -mindepth 1 -maxdepth 1 ! -name script)
if [ -n "$leftover" ]; then
  echo "FAIL: --help left files behind: $leftover"; failed=$((failed + 1))
fi
echo "scripts --help: $((count - failed)) passed, $failed failed"
[ "$failed" -eq 0 ]
