"""Damaged caches heal: a numba, codegen or fingerprint cache file that is not what the package
wrote for this user is detected by its keyed checksum, ignored with a one-line warning and rebuilt, never a crash
or a changed result; a held compile lock is said, then refused, naming its file."""

import errno
import fcntl
import hashlib
import json
import os
import shutil
import stat
import subprocess
import sys
import threading
import time

import pytest
import sympy as sp

from conftest import ROOT
from rotorvib.io import cache_files
from rotorvib.io.cache_files import read_checked, write_checked
from rotorvib.methods import codegen, numba_cache
from rotorvib.methods.numba_cache import MANIFEST, compile_lock, drop_if_stale, record
from rotorvib.models.balancer import parameters, simulate
from rotorvib.pipeline import fingerprint

# --- checked files -----------------------------------------------------------------------------

DAMAGE = {   # kind -> a damaged version of a file's bytes
    "truncated": lambda b: b[: len(b) // 2],
    "garbage": lambda b: os.urandom(len(b)),
    "empty": lambda b: b"",
    "not UTF-8": lambda b: b"\xff\xfe" + b[2:],
    "one byte edited": lambda b: b[:-2] + bytes([b[-2] ^ 1]) + b[-1:],
}


@pytest.mark.parametrize("kind", DAMAGE)
def test_a_damaged_checked_file_reads_as_absent_with_a_warning(tmp_path, kind, capsys):
    path = tmp_path / "entry.json"
    write_checked(path, json.dumps(["rotorvib.io", "numpy"]))
    assert read_checked(path) == '["rotorvib.io", "numpy"]'
    path.write_bytes(DAMAGE[kind](path.read_bytes()))
    assert read_checked(path) is None and not path.exists()
    assert capsys.readouterr().err.count("damaged cache file") == 1


# --- numba's files and the package's manifest ------------------------------------------------

def _package(tmp_path):
    (tmp_path / "a.py").write_text("x = 1\n")
    cache = tmp_path / "__pycache__"
    cache.mkdir()
    drop_if_stale(tmp_path)
    files = {name: cache / name for name in ("a.f-1.py311.nbi", "a.f-1.py311.1.nbc",
                                             "a.g-9.py311.nbi", "a.g-9.py311.1.nbc")}
    for path in files.values():
        path.write_bytes(os.urandom(200))
    record(tmp_path)
    return cache, files


@pytest.mark.parametrize("kind", DAMAGE)
def test_a_damaged_numba_file_drops_its_function_only(tmp_path, kind, capsys):
    cache, files = _package(tmp_path)
    assert not drop_if_stale(tmp_path)                      # intact: kept
    damaged = files["a.f-1.py311.1.nbc"]
    damaged.write_bytes(DAMAGE[kind](damaged.read_bytes()))
    assert drop_if_stale(tmp_path)
    assert [p.name for p in sorted(cache.glob("*.nb?"))] == ["a.g-9.py311.1.nbc",
                                                             "a.g-9.py311.nbi"]
    assert "damaged cache file" in capsys.readouterr().err
    assert not drop_if_stale(tmp_path)                      # healed: nothing more to do


@pytest.mark.parametrize("kind", DAMAGE)
def test_a_damaged_manifest_empties_the_cache_with_a_warning(tmp_path, kind, capsys):
    cache, files = _package(tmp_path)
    manifest = cache / MANIFEST
    manifest.write_bytes(DAMAGE[kind](manifest.read_bytes()))
    assert drop_if_stale(tmp_path) and not any(p.exists() for p in files.values())
    assert "damaged cache file" in capsys.readouterr().err
    assert json.loads(read_checked(manifest))["files"] == {}


def test_a_manifest_of_the_wrong_shape_is_damaged(tmp_path, capsys):
    cache, files = _package(tmp_path)
    write_checked(cache / MANIFEST, json.dumps(["not", "a", "manifest"]))
    assert drop_if_stale(tmp_path) and not any(p.exists() for p in files.values())
    assert "damaged cache file" in capsys.readouterr().err


def test_a_real_damaged_engine_file_is_recompiled_and_gives_the_same_answer(tmp_path):
    """The balancer's compiled integrator with its index overwritten with garbage, in a copy of
    the package whose cache holds the compiled engine: the next process warns once, compiles
    that function again and gives the same peak force as before the damage. (The probe names
    the modules it runs by import, so that this file counts among those that run the
    integrators, tests/conftest.py: it starts once they are compiled.)"""
    probe = (f"from {parameters.__name__} import Balancer, SpeedProfile\n"
             f"from {simulate.__name__} import simulate\n"
             "b = Balancer.from_paper_b(M=1.0, k=1e4, R=0.1, m_bar=0.01, eps_bar=0.012,"
             " zeta=0.01, beta=2.0)\n"
             "print(repr(simulate(b, SpeedProfile(200.0), [0.3, -0.4], 0.05).force_max))\n")
    shutil.copytree(ROOT / "src", tmp_path / "src")

    def run():
        return subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True,
                              env={**os.environ, "PYTHONPATH": str(tmp_path / "src")},
                              timeout=600)

    before = run()
    assert before.returncode == 0, before.stderr
    cache = tmp_path / "src/rotorvib/models/balancer/__pycache__"
    index = next(cache.glob("engine.integrate-*.nbi"))
    index.write_bytes(os.urandom(index.stat().st_size))
    after = run()
    assert after.returncode == 0, after.stderr
    assert after.stdout == before.stdout
    assert after.stderr.count("damaged cache file") == 1 and "engine.integrate" in after.stderr
    assert run().stderr.count("damaged cache file") == 0


# --- generated code and fingerprint memos ------------------------------------------------------

def test_generated_code_runs_only_as_written(tmp_path, capsys):
    """A cache file of generated code is executed only when its checksum matches: a planted or
    edited file (here, one that would return 42) is regenerated, not run; a file that raises
    is regenerated too."""
    module = tmp_path / "expressions.py"
    module.write_text("# the expressions' module\n")
    x = sp.Symbol("x")

    def square():
        return codegen.cached_lambdify("square", lambda: ((x,), x**2), sources=(module,))

    assert square()(3.0) == 9.0
    (path,) = (tmp_path / "__pycache__").glob("square.*.lambdify")
    assert square()(3.0) == 9.0 and capsys.readouterr().err == ""      # from the cache
    planted = "def _lambdifygenerated(x):\n    return 42\n"
    for text in (planted, "raise SystemError('boom')\n", "\udcff",
                 read_checked(path).replace("**2", "**3")):
        path.write_text(text, errors="surrogateescape")
        assert square()(3.0) == 9.0
        assert "damaged cache file" in capsys.readouterr().err
    # a file whose checksum matches but fails to run is regenerated too
    write_checked(path, "raise SystemError('boom')\n")
    assert square()(3.0) == 9.0
    assert "damaged cache file" in capsys.readouterr().err
    # planted with a valid SHA-256 of its text (all a planter without this user's key can
    # compute): not run
    path.write_text(f"{hashlib.sha256(planted.encode()).hexdigest()}\n{planted}")
    assert square()(3.0) == 9.0
    assert "damaged cache file" in capsys.readouterr().err


def test_the_cache_key_is_private_and_without_one_nothing_is_cached(tmp_path, monkeypatch):
    """The key is made once, mode 600 in a folder of mode 700; a key others can read is no key:
    then nothing is written or read back, and results are derived as without a cache."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "cache"))
    cache_files.user_key.cache_clear()
    try:
        key = cache_files.user_key()
        path = cache_files.key_file()
        assert key is not None and stat.S_IMODE(path.stat().st_mode) == 0o600
        assert stat.S_IMODE(path.parent.stat().st_mode) == 0o700
        assert write_checked(tmp_path / "entry", "x") and read_checked(tmp_path / "entry") == "x"
        os.chmod(path, 0o644)
        cache_files.user_key.cache_clear()
        assert cache_files.user_key() is None
        assert not write_checked(tmp_path / "other", "x") and not (tmp_path / "other").exists()
        assert read_checked(tmp_path / "entry") is None
    finally:
        cache_files.user_key.cache_clear()


@pytest.mark.parametrize("stored", ['{"a": 1}', "[1, 2]", '"not a digest"', "null"])
def test_a_fingerprint_memo_of_the_wrong_type_is_rebuilt(tmp_path, monkeypatch, stored, capsys):
    monkeypatch.setattr(fingerprint, "MEMO", tmp_path)
    fingerprint.behaviour_digest.cache_clear()
    digest = fingerprint.behaviour_digest("x = 1\n")
    (entry,) = tmp_path.glob("*.json")
    write_checked(entry, stored)
    fingerprint.behaviour_digest.cache_clear()
    assert fingerprint.behaviour_digest("x = 1\n") == digest
    assert "damaged cache file" in capsys.readouterr().err


# --- the compile lock ----------------------------------------------------------------------------

def test_a_held_compile_lock_is_said_then_refused_naming_its_file(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(numba_cache, "LOCK_NOTICE", 0.2)
    (tmp_path / "__pycache__").mkdir()
    with open(tmp_path / "__pycache__" / numba_cache.LOCK, "a") as other:
        fcntl.flock(other, fcntl.LOCK_EX)          # another process holds it
        start = time.monotonic()
        with pytest.raises(TimeoutError, match=r"compile lock .*numba-compile.lock has been "
                                               r"held by another process for over 1 s"):
            with compile_lock(tmp_path, timeout=1.0):
                pass
        assert 1.0 <= time.monotonic() - start < 5.0
    assert "waiting for the compile lock" in capsys.readouterr().err
    with compile_lock(tmp_path, timeout=1.0):      # released: taken at once
        pass


# --- an unusable key -------------------------------------------------------------------------

@pytest.fixture
def cache_home(tmp_path, monkeypatch):
    """A cache home of the test's own, the key made afresh in it (the process's is forgotten
    before and after)."""
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "home"))
    cache_files.user_key.cache_clear()
    yield tmp_path / "home"
    cache_files.user_key.cache_clear()


def _unusable(kind: str, home, monkeypatch):
    """Make the key file at its place unusable, as ``kind`` says; the reason expected."""
    path = home / "rotorvib/cache.key"
    if kind == "not a folder":
        home.parent.mkdir(exist_ok=True)
        home.write_text("a file where the cache home should be\n")
        return "it cannot be opened (Not a directory)"
    if kind == "read-only home":         # root writes through modes: the file system says no
        def read_only(*args, **kwargs):
            raise OSError(errno.EROFS, os.strerror(errno.EROFS))
        monkeypatch.setattr(cache_files.tempfile, "mkstemp", read_only)
        return "it cannot be made (Read-only file system)"
    path.parent.mkdir(parents=True, mode=0o700)
    key = os.urandom(32).hex() + "\n"
    if kind == "mode 644":
        path.write_text(key)
        path.chmod(0o644)
        return "others can read or write it (mode 644)"
    if kind == "symlink":
        (home / "elsewhere").write_text(key)
        (home / "elsewhere").chmod(0o600)
        path.symlink_to(home / "elsewhere")
        return "it is a symbolic link"
    if kind == "fifo":
        os.mkfifo(path, 0o600)
        return "it is not a regular file"
    if kind == "not a key":
        path.write_text("short\n")
        path.chmod(0o600)
        return "it does not hold a key"
    if os.geteuid() != 0:
        pytest.skip("a key file of another user needs root to make")
    path.write_text(key)
    path.chmod(0o600)
    os.chown(path, 65534, 65534)
    return "it belongs to uid 65534, not to this user"


KINDS = ["mode 644", "symlink", "fifo", "not a key", "not a folder", "read-only home",
         "another user's"]


@pytest.mark.parametrize("kind", KINDS)
def test_an_unusable_key_is_refused_once_naming_the_file_and_why(cache_home, kind, capsys,
                                                                   monkeypatch):
    """Refused, never replaced (others may have read it) and never blocking: a FIFO is opened
    without waiting for a writer (before, the job blocked for ever), in a thread here so that
    a regression fails instead of hanging the tests."""
    why = _unusable(kind, cache_home, monkeypatch)
    got = []
    reader = threading.Thread(target=lambda: got.append(cache_files.user_key()), daemon=True)
    reader.start()
    reader.join(timeout=10)
    assert not reader.is_alive(), "reading the key blocked"
    assert got == [None] and cache_files.user_key() is None
    err = capsys.readouterr().err.splitlines()
    assert err == [f"rotorvib: cache key {cache_files.key_file()} refused: {why}"
                   + err[0].partition(why)[2]]                  # one line, once
    assert "not cached" in err[0]


@pytest.mark.parametrize("kind", ["mode 644", "symlink"])
def test_without_a_usable_key_numbas_cache_is_still_checked_and_kept(tmp_path, cache_home,
                                                                     kind, capsys,
                                                                     monkeypatch):
    """With the key unusable, every engine job dropped numba's files (the manifest could not be
    checked, so each read as damaged) and compiled again, 4 s of CPU becoming 19. Now the
    manifest is sealed without the key: the files a job recorded are kept for the next, and a
    damaged file or an edited source is still found."""
    _unusable(kind, cache_home, monkeypatch)
    (tmp_path / "pkg").mkdir()
    cache, files = _package(tmp_path / "pkg")               # the manifest sealed unkeyed
    assert cache_files.user_key() is None
    assert (cache / MANIFEST).read_text().startswith("sha256:")
    for _ in range(3):                                      # three jobs: nothing dropped
        assert not drop_if_stale(tmp_path / "pkg")
        assert all(p.exists() for p in files.values())
    assert "damaged" not in capsys.readouterr().err
    damaged = files["a.f-1.py311.1.nbc"]
    damaged.write_bytes(DAMAGE["one byte edited"](damaged.read_bytes()))
    assert drop_if_stale(tmp_path / "pkg") and not damaged.exists()
    assert files["a.g-9.py311.1.nbc"].exists()
    assert capsys.readouterr().err.count("damaged cache file") == 1
    (tmp_path / "pkg/a.py").write_text("x = 2\n")           # an edited source: all dropped
    assert drop_if_stale(tmp_path / "pkg") and not any(p.exists() for p in files.values())


def test_a_manifest_sealed_the_other_way_is_rebuilt_without_a_warning(tmp_path, cache_home,
                                                                      capsys):
    """A manifest sealed with the key, read once the key is unusable (or the other way round),
    is not damaged: numba's files are dropped once, silently, and recorded afresh."""
    (tmp_path / "pkg").mkdir()
    cache, files = _package(tmp_path / "pkg")
    assert cache_files.user_key() is not None
    os.chmod(cache_files.key_file(), 0o644)
    cache_files.user_key.cache_clear()
    assert drop_if_stale(tmp_path / "pkg") and not any(p.exists() for p in files.values())
    assert "damaged" not in capsys.readouterr().err
    assert (cache / MANIFEST).read_text().startswith("sha256:")
    os.chmod(cache_files.key_file(), 0o600)                 # the key usable again
    cache_files.user_key.cache_clear()
    for path in files.values():
        path.write_bytes(os.urandom(200))
    assert drop_if_stale(tmp_path / "pkg") and not any(p.exists() for p in files.values())
    assert "damaged" not in capsys.readouterr().err
    assert not (cache / MANIFEST).read_text().startswith("sha256:")


def test_a_valid_file_copied_over_another_is_refused(tmp_path, cache_home, capsys):
    """The seal binds a file's name (a generated function's name and sources' hash): another
    function's valid file copied over it is not run (before, square(3) gave cube's 27)."""
    module = tmp_path / "expressions.py"
    module.write_text("# the expressions' module\n")
    x = sp.Symbol("x")

    def cached(name, power):
        return codegen.cached_lambdify(name, lambda: ((x,), x**power), sources=(module,))

    assert cached("square", 2)(3.0) == 9.0 and cached("cube", 3)(3.0) == 27.0
    (square,) = (tmp_path / "__pycache__").glob("square.*")
    (cube,) = (tmp_path / "__pycache__").glob("cube.*")
    shutil.copyfile(cube, square)
    assert cached("square", 2)(3.0) == 9.0
    assert capsys.readouterr().err.count(f"damaged cache file {square}") == 1
    write_checked(tmp_path / "a", "text")
    shutil.copyfile(tmp_path / "a", tmp_path / "b")
    assert read_checked(tmp_path / "a") == "text" and read_checked(tmp_path / "b") is None
