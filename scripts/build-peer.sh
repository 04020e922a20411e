#!/usr/bin/env bash
# Builds the peer voxelizer, Forceflow's cuda_voxelizer (v0.6), from its public
# source, with the trimesh2 fork its CI builds it against, and our warm-kernel timing driver for
# it (experiments/peer/peer_voxelizer_bench.cu), so that the peer comparison can be rebuilt from
# public source and run in the same device call as bench_voxelizer. The peer's code is never
# committed: it is fetched and extracted into the git-ignored .peer/ of this checkout and built
# there.
#
# Usage: scripts/build-peer.sh [--voxelizer DIR] [--trimesh DIR] [--voxelizer-ref REF]
#                              [--trimesh-ref REF] [--arch SM] [--jobs N] [--no-meshes]
#   By default each source is fetched from its public git repository into .peer/git/ (shallow:
#   the one commit), https://github.com/Forceflow/cuda_voxelizer at tag v0.6 (commit ff93fe6)
#   and https://github.com/Forceflow/trimesh2 at commit 76bc893; the commit each pinned ref
#   names is verified. A fetched source already in .peer/git/ is reused (a rebuild needs no
#   network). Without network, give local copies:
#   --voxelizer DIR   cuda_voxelizer source: a git directory (bare mirror or checkout; REF is
#                     extracted with git archive) or a plain source folder (copied as it is,
#                     unverified). Default $PEER_VOXELIZER_SRC, else fetched
#   --trimesh DIR     trimesh2 source, likewise. Default $PEER_TRIMESH_SRC, else fetched
#   --voxelizer-ref, --trimesh-ref   commit, tag or branch to build instead of the pinned one
#                     (not verified). The peer's CI pins trimesh2 tag 2022.03.04; 76bc893
#                     differs from it only in CI, README and MSVC project files, not in
#                     include/ or libsrc/.
#   --arch SM         CUDA architecture (default 90: sm_90 code and compute_90 PTX, as deepvox's
#                     own "90-real;90-virtual")
#   --jobs N          parallel build jobs (default 1)
#   --no-meshes       skip writing the benchmark meshes (experiments/peer/write_bench_meshes.py)
#   $PEER_VOXELIZER_URL, $PEER_TRIMESH_URL   fetch from another URL (a fork or a mirror server)
# Writes, under .peer/ of this checkout:
#   git/cuda_voxelizer.git, git/trimesh2.git  the fetched sources (bare, shallow), when fetched
#   src/cuda_voxelizer/, src/trimesh2/  the extracted sources (trimesh2's libtrimesh.a is built
#                                       in src/trimesh2/lib.Linux64/, as upstream does)
#   build/cuda_voxelizer/               the peer's CMake build
#   bin/cuda_voxelizer                  the peer's own program (Release, -O3), with the shared
#                                       CUDA runtime it links beside it (bin/libcudart.so.*)
#   bin/peer_voxelizer_bench            our driver, compiled against the peer's src/voxelize.cu
#   meshes/{cube,bunny2,bunny3}.obj     bench_voxelizer's meshes as OBJ (needs python3)
#   PEER.txt                            commits, where they came from, compilers and every flag
# Patches to the peer's source: none (it builds unchanged with nvcc 13.0 and g++ 12).
# Exit status: 0 built; 2 usage error, sources or tools missing, a repository unreachable or a
# pinned ref naming another commit; otherwise the failing step's.
# shellcheck disable=SC2016  # '$ORIGIN' (for ld.so) and make's '$(CXXFLAGS)' are meant literally
set -euo pipefail
shopt -s inherit_errexit  # a failing step inside $(...) stops the script too

repo=$(cd "$(dirname "$0")/.." && pwd)
peer="$repo/.peer"
vox_url=${PEER_VOXELIZER_URL:-https://github.com/Forceflow/cuda_voxelizer}
tm_url=${PEER_TRIMESH_URL:-https://github.com/Forceflow/trimesh2}
# The pinned sources: the ref built by default and the commit it must name.
vox_pin_ref=v0.6
vox_pin=ff93fe65a9144c1dc9f11d22e786ad698387767b
tm_pin_ref=76bc89310b45279ff3c40415a6f6d5789479b42f
tm_pin=76bc89310b45279ff3c40415a6f6d5789479b42f
vox_src=${PEER_VOXELIZER_SRC:-}
tm_src=${PEER_TRIMESH_SRC:-}
vox_ref=
tm_ref=
arch=90
jobs=1
meshes=1

die() {  # status message...
  local status=$1
  shift
  echo "build-peer.sh: error: $*" >&2
  exit "$status"
}
usage() { sed -n '/^# Usage/,/^# shellcheck/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2; exit 2; }

while [ $# -gt 0 ]; do
  case $1 in
    --voxelizer) vox_src=${2:?}; shift 2 ;;
    --trimesh) tm_src=${2:?}; shift 2 ;;
    --voxelizer-ref) vox_ref=${2:?}; shift 2 ;;
    --trimesh-ref) tm_ref=${2:?}; shift 2 ;;
    --arch) arch=${2:?}; shift 2 ;;
    --jobs) jobs=${2:?}; shift 2 ;;
    --no-meshes) meshes=0; shift ;;
    -h | --help) usage ;;
    *) echo "build-peer.sh: unknown argument '$1'" >&2; usage ;;
  esac
done
[[ $arch =~ ^[0-9]+[a-z]?$ ]] || die 2 "--arch wants a number such as 90, not '$arch'"
[[ $jobs =~ ^[1-9][0-9]*$ ]] || die 2 "--jobs wants a positive integer, not '$jobs'"

for tool in git nvcc cmake make g++ ar; do
  command -v "$tool" > /dev/null || die 2 "'$tool' is not on the PATH"
done

# Fetches REF of URL into the bare repository DIR (.peer/git/NAME.git), the one commit where
# the server allows it (GitHub does, for tags and commit hashes), else everything; prints the
# fetched commit. A DIR that already holds PIN is reused when REF is the pinned one.
fetch_source() {  # name option url ref pinned_ref pin dir
  local name=$1 option=$2 url=$3 ref=$4 pinned_ref=$5 pin=$6 dir=$7 commit
  if [ "$ref" = "$pinned_ref" ] && git -C "$dir" cat-file -e "$pin^{commit}" 2> /dev/null; then
    echo "build-peer.sh: $name $ref already fetched in $dir" >&2
    echo "$pin"
    return
  fi
  echo "build-peer.sh: fetching $name $ref from $url" >&2
  GIT_TERMINAL_PROMPT=0 timeout 120 git ls-remote --exit-code "$url" HEAD > /dev/null 2>&1 ||
    die 2 "cannot reach $url (no network, or no such repository): give $option DIR, a local" \
      "mirror or checkout of $name (git clone $url)"
  rm -rf "$dir"
  git init -q --bare "$dir"
  if GIT_TERMINAL_PROMPT=0 git -C "$dir" fetch -q --depth 1 "$url" "$ref" 2> /dev/null; then
    commit=$(git -C "$dir" rev-parse --verify "FETCH_HEAD^{commit}")
  else
    GIT_TERMINAL_PROMPT=0 git -C "$dir" fetch -q --tags "$url" '+refs/heads/*:refs/heads/*' ||
      die 2 "fetching $url failed"
    commit=$(git -C "$dir" rev-parse --verify --quiet "$ref^{commit}") ||
      die 2 "$url has no commit, tag or branch '$ref'"
  fi
  git -C "$dir" update-ref refs/heads/fetched "$commit"  # a ref: no git gc drops the commit
  echo "$commit"
}
# Checks source DIR before anything is written: prints the commit that REF names in it, or
# "unknown" for a plain folder (copied as it is; no ref given for it); KEY is a file the source
# must hold; OPTION names the option that gives DIR.
resolve() {  # name option dir ref ref_given key
  local name=$1 option=$2 dir=$3 ref=$4 ref_given=$5 key=$6 commit
  [ -d "$dir" ] || die 2 "$name source '$dir' does not exist (give $option DIR)"
  if [ -e "$dir/.git" ] || [ "$(git -C "$dir" rev-parse --is-bare-repository 2> /dev/null)" = true ]
  then
    commit=$(git -C "$dir" rev-parse --verify --quiet "$ref^{commit}") ||
      die 2 "$name source '$dir' has no commit, tag or branch '$ref'"
    git -C "$dir" cat-file -e "$commit:$key" 2> /dev/null ||
      die 2 "$name source '$dir' at $ref has no $key: not the $name source"
    echo "$commit"
  elif [ -f "$dir/$key" ]; then
    [ -z "$ref_given" ] ||
      die 2 "$name source '$dir' is no git repository: a ref ($ref_given) cannot apply"
    echo "build-peer.sh: $name source '$dir' is a plain folder: built as it is, its commit" \
      "unverified" >&2
    echo unknown
  else
    die 2 "$name source '$dir' is neither a git repository nor a folder holding $key"
  fi
}
# The commit to build of one source: fetched or from DIR, checked against the pin when the
# pinned ref is built. Sets source_commit, source_origin and source_dir (the git directory or
# folder to extract it from).
source_of() {  # name option url src ref pinned_ref pin key
  local name=$1 option=$2 url=$3 src=$4 ref=${5:-$6} pinned_ref=$6 pin=$7 key=$8
  if [ -n "$src" ]; then
    source_commit=$(resolve "$name" "$option" "$src" "$ref" "$5" "$key")
    source_origin="ref $ref of $src"
    source_dir=$src
  else
    source_dir="$peer/git/$name.git"
    source_commit=$(fetch_source "$name" "$option" "$url" "$ref" "$pinned_ref" "$pin" \
      "$source_dir")
    git -C "$source_dir" cat-file -e "$source_commit:$key" 2> /dev/null ||
      die 2 "$url at $ref has no $key: not the $name source"
    source_origin="ref $ref of $url"
  fi
  if [ "$ref" = "$pinned_ref" ] && [ "$source_commit" != unknown ] &&
      [ "$source_commit" != "$pin" ]; then
    die 2 "$name ref $ref in ${src:-$url} is commit $source_commit, not the pinned $pin" \
      "(another repository, or a moved tag: check the source, or build it with its own ref" \
      "given explicitly)"
  fi
  if [ "$ref" = "$pinned_ref" ] && [ "$source_commit" = "$pin" ]; then
    source_origin="$source_origin, the pinned commit"
  fi
}

# Writes the source at COMMIT of DIR into DEST (a plain folder's files as they are).
extract() {  # dir commit dest
  rm -rf "$3"
  mkdir -p "$3"
  if [ "$2" = unknown ]; then
    cp -a "$1/." "$3/"
    rm -rf "$3/.git"
  else
    git -C "$1" archive "$2" | tar -x -C "$3"
  fi
}

source_of cuda_voxelizer --voxelizer "$vox_url" "$vox_src" "$vox_ref" "$vox_pin_ref" \
  "$vox_pin" src/voxelize.cu
vox_commit=$source_commit vox_origin=$source_origin vox_git=$source_dir
source_of trimesh2 --trimesh "$tm_url" "$tm_src" "$tm_ref" "$tm_pin_ref" "$tm_pin" \
  libsrc/TriMesh_io.cc
tm_commit=$source_commit tm_origin=$source_origin tm_git=$source_dir
[ -f "$repo/experiments/peer/peer_voxelizer_bench.cu" ] ||
  die 2 "experiments/peer/peer_voxelizer_bench.cu is missing from this checkout"
extract "$vox_git" "$vox_commit" "$peer/src/cuda_voxelizer"
extract "$tm_git" "$tm_commit" "$peer/src/trimesh2"
vox_dir="$peer/src/cuda_voxelizer"
tm_dir="$peer/src/trimesh2"
echo "build-peer.sh: cuda_voxelizer $vox_commit, trimesh2 $tm_commit"

# trimesh2: only libsrc (libtrimesh.a), with its own Makefile and flags, as the peer's CI does
# (`make all` there also builds gluit and the utilities, which the voxelizer does not use).
# Without OpenGL headers its two GL helpers (unused by the voxelizer) are left out.
tm_files=()
if ! printf '#include <GL/gl.h>\n' | g++ -fsyntax-only -x c++ - 2> /dev/null; then
  # shellcheck disable=SC1003  # '\\' is tr's backslash, not an escaped quote
  tm_files=("CCFILES=$(sed -n '/^CCFILES/,/^$/p' "$tm_dir/libsrc/Makefile" | tr -d '\\' |
    sed 's/^CCFILES *=//' | tr -s ' \t\n' ' ' | sed 's/GLCamera.cc//; s/GLManager.cc//')")
  echo "build-peer.sh: no <GL/gl.h>: libtrimesh without GLCamera.cc and GLManager.cc"
fi
make -C "$tm_dir/libsrc" -j"$jobs" "${tm_files[@]}"
tm_lib="$tm_dir/lib.Linux64"
[ -f "$tm_lib/libtrimesh.a" ] || die 1 "trimesh2 built no $tm_lib/libtrimesh.a"

# cuda_voxelizer with its own CMakeLists: Release (-O3 -DNDEBUG for C++ and CUDA).
build="$peer/build/cuda_voxelizer"
rm -rf "$build"
cuda_archs="$arch-real;$arch-virtual"
cmake -S "$vox_dir" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CUDA_COMPILER="$(command -v nvcc)" -DCMAKE_CUDA_ARCHITECTURES="$cuda_archs" \
  -DCMAKE_CXX_FLAGS_RELEASE="-O3 -DNDEBUG" -DCMAKE_CUDA_FLAGS_RELEASE="-O3 -DNDEBUG" \
  -DTrimesh2_INCLUDE_DIR="$tm_dir/include" -DTrimesh2_LINK_DIR="$tm_lib" \
  -DCMAKE_BUILD_RPATH='$ORIGIN'
if ! cmake --build "$build" -j "$jobs" -- VERBOSE=1 > "$build/build.log" 2>&1; then
  tail -n 40 "$build/build.log" >&2
  die 1 "the cuda_voxelizer build failed (log: $build/build.log)"
fi
grep -iE 'warning|error' "$build/build.log" | sort | uniq -c | sort -rn | head -n 20 || true
rm -rf "${peer:?}/bin"  # also so that ldd below finds the runtime outside it
mkdir -p "$peer/bin"
cp "$build/cuda_voxelizer" "$peer/bin/cuda_voxelizer"
# Its CMakeLists links the shared CUDA runtime (CUDA::cudart), found through an rpath to this
# machine's CUDA folder; the copy beside it ($ORIGIN comes first) travels with .peer/bin.
cudart=$(ldd "$peer/bin/cuda_voxelizer" | awk '/libcudart\.so/ {print $3}')
[ -f "$cudart" ] || die 1 "cuda_voxelizer links no libcudart.so that ldd can find"
cp -L "$cudart" "$peer/bin/"

# Our driver: one translation unit that includes the peer's src/voxelize.cu (its kernel as is).
driver_flags=(-O3 -std=c++17 -DNDEBUG
  "-gencode=arch=compute_$arch,code=[sm_$arch,compute_$arch]"
  -Xcompiler=-fopenmp -I"$vox_dir/src" -I"$tm_dir/include")
nvcc "${driver_flags[@]}" "$repo/experiments/peer/peer_voxelizer_bench.cu" \
  -L"$tm_lib" -ltrimesh -lgomp -o "$peer/bin/peer_voxelizer_bench"

if [ "$meshes" = 1 ]; then
  if command -v python3 > /dev/null; then
    python3 "$repo/experiments/peer/write_bench_meshes.py" "$peer/meshes"
  else
    echo "build-peer.sh: no python3: meshes not written" \
      "(run experiments/peer/write_bench_meshes.py)" >&2
  fi
fi

flags_of() { grep -m1 -E -e "$1" "$build/build.log" | sed 's/^ *//' || echo "(not in the log)"; }
{
  echo "# .peer/ written by scripts/build-peer.sh on $(date -u +%Y-%m-%dT%H:%M:%SZ) ($(uname -m))"
  echo "cuda_voxelizer: $vox_commit ($vox_origin)"
  echo "trimesh2: $tm_commit ($tm_origin)"
  echo "patches: none"
  echo "nvcc: $(nvcc --version | tail -n 2 | tr '\n' ' ')"
  echo "g++: $(g++ --version | head -n 1)"
  echo "cmake: $(cmake --version | head -n 1)"
  echo "arch: $cuda_archs"
  echo "trimesh2 libsrc CXXFLAGS: $(cd "$tm_dir/libsrc" && make -s --no-print-directory \
    -f Makefile -f <(printf 'print-flags:\n\t@echo $(CXXFLAGS)\n') print-flags 2> /dev/null)" \
    "${tm_files[*]}"
  echo "cuda_voxelizer .cu compile: $(flags_of 'nvcc.* -c .*voxelize\.cu')"
  echo "cuda_voxelizer .cpp compile: $(flags_of '(c\+\+|g\+\+).* -c .*main\.cpp')"
  echo "cuda_voxelizer link: $(flags_of '-o cuda_voxelizer')"
  echo "peer_voxelizer_bench: nvcc ${driver_flags[*]} experiments/peer/peer_voxelizer_bench.cu" \
    "-L$tm_lib -ltrimesh -lgomp"
  for b in cuda_voxelizer peer_voxelizer_bench; do
    echo "bin/$b: $(stat -c %s "$peer/bin/$b") bytes," \
      "sha256 $(sha256sum "$peer/bin/$b" | cut -c1-64)"
  done
  echo "bin/$(basename "$cudart"): copied from $cudart"
  for m in "$peer"/meshes/*.obj; do
    [ -f "$m" ] && echo "meshes/$(basename "$m"): sha256 $(sha256sum "$m" | cut -c1-64)"
  done
  true
} > "$peer/PEER.txt"
cat "$peer/PEER.txt"
