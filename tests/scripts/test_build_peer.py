#!/usr/bin/env python3
"""Tests of scripts/build-peer.sh's source step on the CPU, without network: the peer's
sources are fetched from a git URL (here local stand-in repositories through
$PEER_VOXELIZER_URL) into .peer/git/, shallow where the server allows it; the pinned ref must
name the pinned commit; an unreachable repository, a missing folder and a moved pin stop it
with exit 2 and a message naming the source, before anything is built. The script runs from a
copy of itself in a scratch tree, so it writes that tree's .peer/, never this checkout's. Also
bash -n over every script and shellcheck (when installed) over build-peer.sh and ab-bench.sh."""
import glob
import os
import shutil
import subprocess
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(ROOT, "scripts", "build-peer.sh")
PINNED_VOXELIZER = "ff93fe65a9144c1dc9f11d22e786ad698387767b"
TOOLS = ["git", "nvcc", "cmake", "make", "g++", "ar"]
UNREACHABLE = "http://127.0.0.1:9/Forceflow/trimesh2"  # the discard port: connection refused


def git(cwd, *args):
    return subprocess.run(["git", "-C", cwd, *args], check=True, capture_output=True,
                          text=True).stdout.strip()


def stand_in_repository(path, key, tag):
    """A git repository of two commits holding KEY, the first tagged TAG; returns both hashes."""
    os.makedirs(os.path.join(path, os.path.dirname(key)))
    git(path, "init", "-q")
    commits = []
    for n in (1, 2):
        with open(os.path.join(path, key), "w") as f:
            f.write(f"// version {n}\n")
        git(path, "add", key)
        git(path, "-c", "user.name=t", "-c", "user.email=t@t", "commit", "-q", "-m", f"v{n}")
        commits.append(git(path, "rev-parse", "HEAD"))
        if n == 1:
            git(path, "tag", tag)
    return commits


@unittest.skipUnless(all(shutil.which(t) for t in TOOLS),
                     "build-peer.sh needs " + ", ".join(TOOLS) + " on the PATH")
class SourceStep(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="build-peer-test-")
        self.tree = os.path.join(self.dir, "tree")
        os.makedirs(os.path.join(self.tree, "scripts"))
        os.makedirs(os.path.join(self.tree, "experiments", "peer"))
        shutil.copy(SCRIPT, os.path.join(self.tree, "scripts"))
        open(os.path.join(self.tree, "experiments", "peer", "peer_voxelizer_bench.cu"), "w").close()
        self.upstream = os.path.join(self.dir, "cuda_voxelizer")
        self.commits = stand_in_repository(self.upstream, "src/voxelize.cu", "v0.6")
        self.peer_git = os.path.join(self.tree, ".peer", "git", "cuda_voxelizer.git")

    def tearDown(self):
        shutil.rmtree(self.dir)

    def run_script(self, *args, voxelizer_url=None, trimesh_url=UNREACHABLE):
        env = dict(os.environ, PEER_TRIMESH_URL=trimesh_url, GIT_CONFIG_NOSYSTEM="1")
        env.pop("PEER_VOXELIZER_SRC", None)
        env.pop("PEER_TRIMESH_SRC", None)
        env["PEER_VOXELIZER_URL"] = voxelizer_url or "file://" + self.upstream
        return subprocess.run(["bash", os.path.join(self.tree, "scripts", "build-peer.sh"), *args],
                              capture_output=True, text=True, env=env, cwd=self.dir)

    def test_an_unreachable_repository_stops_with_exit_2_before_writing(self):
        out = self.run_script(voxelizer_url="http://127.0.0.1:9/Forceflow/cuda_voxelizer")
        self.assertEqual(out.returncode, 2, out.stderr)
        self.assertIn("error: cannot reach http://127.0.0.1:9/Forceflow/cuda_voxelizer", out.stderr)
        self.assertIn("give --voxelizer DIR", out.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.tree, ".peer")))

    def test_the_pinned_ref_must_name_the_pinned_commit(self):
        out = self.run_script()
        self.assertEqual(out.returncode, 2, out.stderr)
        self.assertIn(f"cuda_voxelizer ref v0.6 in file://{self.upstream} is commit "
                      f"{self.commits[0]}, not the pinned {PINNED_VOXELIZER}", out.stderr)
        out = self.run_script("--voxelizer", self.upstream)
        self.assertEqual(out.returncode, 2, out.stderr)
        self.assertIn(f"in {self.upstream} is commit {self.commits[0]}, not the pinned", out.stderr)

    def test_a_tag_is_fetched_shallow_into_peer_git(self):
        out = self.run_script("--voxelizer-ref", "v0.6")
        self.assertEqual(out.returncode, 2, out.stderr)  # the pin check, after the fetch
        self.assertEqual(git(self.peer_git, "rev-parse", "refs/heads/fetched"), self.commits[0])
        self.assertEqual(git(self.peer_git, "rev-parse", "--is-shallow-repository"), "true")

    def test_another_ref_is_fetched_and_built_unverified(self):
        for ref, commit in (("master", self.commits[1]), (self.commits[0], self.commits[0])):
            git(self.upstream, "branch", "-M", "master")
            out = self.run_script("--voxelizer-ref", ref)
            # The voxelizer's step passed; the run stops at trimesh2's unreachable repository.
            self.assertEqual(out.returncode, 2, out.stderr)
            self.assertIn(f"error: cannot reach {UNREACHABLE}", out.stderr)
            self.assertEqual(git(self.peer_git, "rev-parse", "refs/heads/fetched"), commit)

    def test_fetched_sources_are_extracted_into_peer_src(self):
        trimesh = os.path.join(self.dir, "trimesh2")
        tm_commits = stand_in_repository(trimesh, "libsrc/TriMesh_io.cc", "2022.03.04")
        out = self.run_script("--voxelizer-ref", self.commits[0], "--trimesh-ref", tm_commits[1],
                              "--no-meshes", trimesh_url="file://" + trimesh)
        self.assertIn(f"cuda_voxelizer {self.commits[0]}, trimesh2 {tm_commits[1]}", out.stdout)
        src = os.path.join(self.tree, ".peer", "src")
        with open(os.path.join(src, "cuda_voxelizer", "src", "voxelize.cu")) as f:
            self.assertEqual(f.read(), "// version 1\n")
        with open(os.path.join(src, "trimesh2", "libsrc", "TriMesh_io.cc")) as f:
            self.assertEqual(f.read(), "// version 2\n")
        self.assertFalse(os.path.exists(os.path.join(src, "cuda_voxelizer", ".git")))
        # The stand-in trimesh2 has no Makefile: the build step fails with make's status.
        self.assertNotEqual(out.returncode, 0)
        self.assertFalse(os.path.exists(os.path.join(self.tree, ".peer", "bin")))

    def test_a_ref_the_repository_lacks_is_exit_2(self):
        out = self.run_script("--voxelizer-ref", "no-such-tag")
        self.assertEqual(out.returncode, 2)
        self.assertIn(f"file://{self.upstream} has no commit, tag or branch 'no-such-tag'",
                      out.stderr)

    def test_a_fetched_pinned_source_is_reused_without_network(self):
        self.run_script("--voxelizer-ref", self.commits[0])
        # Pretend the fetched commit is the pinned one: a copy of the script pinned to it.
        script = os.path.join(self.tree, "scripts", "build-peer.sh")
        with open(script) as f:
            text = f.read().replace(PINNED_VOXELIZER, self.commits[0])
        with open(script, "w") as f:
            f.write(text.replace("vox_pin_ref=v0.6", "vox_pin_ref=" + self.commits[0]))
        out = self.run_script(voxelizer_url="http://127.0.0.1:9/Forceflow/cuda_voxelizer")
        self.assertIn("already fetched", out.stderr)
        self.assertIn(f"error: cannot reach {UNREACHABLE}", out.stderr)

    def test_a_missing_folder_or_a_wrong_source_is_exit_2(self):
        out = self.run_script("--voxelizer", os.path.join(self.dir, "nowhere"))
        self.assertEqual(out.returncode, 2)
        self.assertIn("nowhere' does not exist (give --voxelizer DIR)", out.stderr)
        out = self.run_script("--voxelizer", self.upstream, "--voxelizer-ref", "no-such-tag")
        self.assertEqual(out.returncode, 2)
        self.assertIn("has no commit, tag or branch 'no-such-tag'", out.stderr)
        os.makedirs(os.path.join(self.dir, "other", "src"))
        out = self.run_script("--voxelizer", os.path.join(self.dir, "other"))
        self.assertEqual(out.returncode, 2)
        self.assertIn("is neither a git repository nor a folder holding src/voxelize.cu",
                      out.stderr)
        plain = os.path.join(self.dir, "plain")
        shutil.copytree(self.upstream, plain, ignore=shutil.ignore_patterns(".git"))
        out = self.run_script("--voxelizer", plain, "--voxelizer-ref", "v0.6")
        self.assertEqual(out.returncode, 2)
        self.assertIn("is no git repository: a ref (v0.6) cannot apply", out.stderr)
        out = self.run_script("--voxelizer", plain)
        self.assertIn("is a plain folder: built as it is, its commit unverified", out.stderr)
        self.assertIn(f"error: cannot reach {UNREACHABLE}", out.stderr)


class Syntax(unittest.TestCase):
    def test_every_script_parses(self):
        for script in sorted(glob.glob(os.path.join(ROOT, "scripts", "*.sh"))):
            out = subprocess.run(["bash", "-n", script], capture_output=True, text=True)
            self.assertEqual(out.returncode, 0, script + ": " + out.stderr)

    @unittest.skipUnless(shutil.which("shellcheck"), "shellcheck is not installed")
    def test_the_benchmark_scripts_pass_shellcheck(self):
        for name in ("build-peer.sh", "ab-bench.sh"):
            out = subprocess.run(["shellcheck", os.path.join(ROOT, "scripts", name)],
                                 capture_output=True, text=True)
            self.assertEqual(out.returncode, 0, name + ":\n" + out.stdout)


if __name__ == "__main__":
    unittest.main()
