#!/usr/bin/env bash
# Builds the peer voxelizer of issue 40, Forceflow's cuda_voxelizer (v0.6), from its public
# source, with the trimesh2 fork its CI builds it against, and our warm-kernel timing driver for
# it (experiments/peer/peer_voxelizer_bench.cu), so that the peer comparison can be rebuilt from
# public source and run in the same device call as bench_voxelizer. The peer's code is never
# committed: it is extracted into the git-ignored .peer/ of this checkout and built there.
#
# Usage: scripts/build-peer.sh [--voxelizer DIR] [--trimesh DIR] [--voxelizer-ref REF]
#                              [--trimesh-ref REF] [--arch SM] [--jobs N] [--no-meshes]
#   --voxelizer DIR   cuda_voxelizer source: a git directory (bare mirror or checkout; REF is
#                     extracted with git archive) or a plain source folder (copied as it is).
#                     Default $PEER_VOXELIZER_SRC, else /work/.mirror/Forceflow+cuda_voxelizer/repo
#   --trimesh DIR     trimesh2 source, likewise. Default $PEER_TRIMESH_SRC, else
#                     /work/.mirror/Forceflow+trimesh2/repo
#   --voxelizer-ref, --trimesh-ref   commit, tag or branch to extract (default HEAD). The
#                     peer's CI pins trimesh2 tag 2022.03.04; HEAD differs from it only in CI,
#                     README and MSVC project files, not in include/ or libsrc/.
#   --arch SM         CUDA architecture (default 90: sm_90 code and compute_90 PTX, as deepvox's
#                     own "90-real;90-virtual")
#   --jobs N          parallel build jobs (default 1)
#   --no-meshes       skip writing the benchmark meshes (experiments/peer/write_bench_meshes.py)
# Writes, under .peer/ of this checkout:
#   src/cuda_voxelizer/, src/trimesh2/  the extracted sources (trimesh2's libtrimesh.a is built
#                                       in src/trimesh2/lib.Linux64/, as upstream does)
#   build/cuda_voxelizer/               the peer's CMake build
#   bin/cuda_voxelizer                  the peer's own program (Release, -O3), with the shared
#                                       CUDA runtime it links beside it (bin/libcudart.so.*)
#   bin/peer_voxelizer_bench            our driver, compiled against the peer's src/voxelize.cu
#   meshes/{cube,bunny2,bunny3}.obj     bench_voxelizer's meshes as OBJ (needs python3)
#   PEER.txt                            commits, compilers and every flag used
# Patches to the peer's source: none (it builds unchanged with nvcc 13.0 and g++ 12).
# Exit status: 0 built; 2 usage error, sources or tools missing; otherwise the failing step's.
# shellcheck disable=SC2016  # '$ORIGIN' (for ld.so) and make's '$(CXXFLAGS)' are meant literally
set -euo pipefail

repo=$(cd "$(dirname "$0")/.." && pwd)
peer="$repo/.peer"
vox_src=${PEER_VOXELIZER_SRC:-/work/.mirror/Forceflow+cuda_voxelizer/repo}
tm_src=${PEER_TRIMESH_SRC:-/work/.mirror/Forceflow+trimesh2/repo}
vox_ref=HEAD
tm_ref=HEAD
arch=90
jobs=1
meshes=1

die() {  # status message...
  local status=$1
  shift
  echo "build-peer.sh: error: $*" >&2
  exit "$status"
}
usage() { sed -n '8,32p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }

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

for tool in nvcc cmake make g++ ar; do
  command -v "$tool" > /dev/null || die 2 "'$tool' is not on the PATH"
done

# Checks source DIR before anything is written: prints the commit that REF names in it, or
# "unknown" for a plain folder (copied as it is); KEY is a file the source must hold; OPTION
# names the option that gives DIR.
resolve() {  # name option dir ref key
  local name=$1 option=$2 dir=$3 ref=$4 key=$5 commit
  [ -d "$dir" ] ||
    die 2 "$name source '$dir' does not exist (give $option DIR, or mirror github:Forceflow/$name)"
  if git -C "$dir" rev-parse --git-dir > /dev/null 2>&1 &&
      commit=$(git -C "$dir" rev-parse --verify --quiet "$ref^{commit}"); then
    git -C "$dir" cat-file -e "$commit:$key" 2> /dev/null ||
      die 2 "$name source '$dir' at $ref has no $key: not the $name source"
    echo "$commit"
  elif [ -f "$dir/$key" ]; then
    [ "$ref" = HEAD ] || die 2 "$name source '$dir' is no git directory: a ref ($ref) cannot apply"
    echo unknown
  else
    die 2 "$name source '$dir' has neither git ref '$ref' nor the file $key"
  fi
}
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

vox_commit=$(resolve cuda_voxelizer --voxelizer "$vox_src" "$vox_ref" src/voxelize.cu)
tm_commit=$(resolve trimesh2 --trimesh "$tm_src" "$tm_ref" libsrc/TriMesh_io.cc)
[ -f "$repo/experiments/peer/peer_voxelizer_bench.cu" ] ||
  die 2 "experiments/peer/peer_voxelizer_bench.cu is missing from this checkout"
extract "$vox_src" "$vox_commit" "$peer/src/cuda_voxelizer"
extract "$tm_src" "$tm_commit" "$peer/src/trimesh2"
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
  echo "cuda_voxelizer: $vox_commit (ref $vox_ref of $vox_src)"
  echo "trimesh2: $tm_commit (ref $tm_ref of $tm_src)"
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
