"""The guarantee hunter's Python leg (docs/hardening.md): random small scenes of every damping
kind and integrator, written as scene files; the Python module's exact_limits and the CLI's
`bounds` on the same file must give the same verdict and limits, and both must refuse the same
out-of-range numbers. Needs DAMPBOUND_CLI (the dampbound program; ctest sets it)."""
import math
import os
import re
import subprocess

import numpy as np
import pytest

import dampbound

CLI = os.environ.get("DAMPBOUND_CLI")
pytestmark = pytest.mark.skipif(not CLI, reason="DAMPBOUND_CLI is not set")
INTEGRATORS = ["semi-implicit-euler", "forward-euler", "verlet", "rk4", "implicit-euler"]


def scene_text(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(2, 8))
    x = rng.random((n, 3)) * 2
    lines = [f'name = "hunted-{seed}"', "watch = 1"]
    for i in range(n):
        lines += ["[[node]]", f"x = [{x[i, 0]!r}, {x[i, 1]!r}, {x[i, 2]!r}]"]
        if i == 0:
            lines.append("fixed = true")
        else:
            lines.append(f"mass_scale = {rng.uniform(0.2, 5)!r}")
            lines.append(f"anchor_scale = {rng.uniform(0.1, 2)!r}")
    for i in range(1, n):
        lines += ["[[spring]]", f"nodes = [{int(rng.integers(0, i))}, {i}]",
                  f"kappa_scale = {rng.uniform(0.5, 3)!r}", f"kd_scale = {rng.uniform(0, 2)!r}"]
    m, kappa = 10 ** rng.uniform(-3, 1), 10 ** rng.uniform(-3, 1)
    crit, omega = 2 * math.sqrt(m * kappa), math.sqrt(kappa / m)
    kinds = int(rng.integers(0, 8))
    lines += ["[params]", f"m = {m!r}", f"kappa = {kappa!r}",
              f"gamma = {(rng.uniform(0, 2) * crit if kinds & 1 else 0.0)!r}",
              f"kd = {(rng.uniform(0, 1) * crit if kinds & 2 else 0.0)!r}",
              f"rayleigh_mass = {(rng.uniform(0, 1) * omega if kinds & 4 else 0.0)!r}",
              f"dt = {rng.uniform(0.05, 2.5) / omega!r}",
              f'integrator = "{INTEGRATORS[int(rng.integers(0, 5))]}"',
              "[[perturb]]", "node = 1", "displacement = [0.0, 0.001, 0.0]"]
    return "\n".join(lines) + "\n"


def cli_rows(path):
    out = subprocess.run([CLI, "bounds", str(path)], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    rows = {}
    for line in out.stdout.splitlines():
        m = re.match(r"^(exact (?:spectral radius|gamma interval|dt limit)) \(([a-z0-9-]+)\)\s+"
                     r"(\S+)(?:\s+\S+)?\s+(within|BEYOND|n/a)\s", line)
        if m:
            rows[m.group(1)] = (m.group(3), m.group(4))
    return rows


def close(text, value):
    if text in ("inf", "-inf", "nan") or not math.isfinite(value):
        return text.lstrip("-") == repr(abs(value)) or (text == "nan" and math.isnan(value)) \
            or (text == "inf" and value == math.inf)
    return abs(float(text) - value) <= 1e-3 * abs(value) + 1e-300


@pytest.mark.parametrize("seed", range(12))
def test_python_and_cli_agree(tmp_path, seed):
    path = tmp_path / "s.toml"
    path.write_text(scene_text(seed))
    e = dampbound.exact_limits(dampbound.load_scene(str(path)))
    rows = cli_rows(path)
    assert "exact dt limit" in rows, rows
    value, verdict = rows["exact spectral radius"]
    assert (verdict == "within") == e.stable or verdict == "n/a", (verdict, e.stable, e.method)
    dt_text, _ = rows["exact dt limit"]
    if math.isnan(e.dt_max):
        assert dt_text in ("nan", "n/a"), dt_text
    else:
        assert close(dt_text, e.dt_max), (dt_text, e.dt_max)


def test_both_refuse_numbers_that_overflow(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(scene_text(3).replace("[params]", "[params]\nzeta = 1e300", 1)
                    .replace("\ngamma = ", "\n# gamma = "))
    out = subprocess.run([CLI, "bounds", str(path)], capture_output=True, text=True)
    assert out.returncode == 2 and "out of range" in out.stderr + out.stdout or \
        "overflows" in out.stderr + out.stdout, out
    with pytest.raises(ValueError, match="overflow|out of range"):
        dampbound.exact_limits(dampbound.load_scene(str(path)))
