"""Warps, pdfs and chi-square tests against the CLI's values; the samplers' point sets."""
import math
import time

import numpy as np
import pytest

import penumbra

CASES = [("uniform-square", None), ("tent", None), ("uniform-disk", None), ("concentric-disk", None),
         ("uniform-sphere", None), ("uniform-hemisphere", None), ("cosine-hemisphere", None),
         ("uniform-cone", 0.9), ("beckmann", 0.2)]


def _param_args(param):
    return [] if param is None else ["--param", param]


def _floats(text):
    return np.array([[float(x) for x in line.split()] for line in text.splitlines() if line.strip()])


def test_every_warp_name_is_covered():
    assert sorted(penumbra.warp_names()) == sorted(name for name, _ in CASES)


@pytest.mark.parametrize("name,param", CASES)
def test_warp_and_pdf_match_cli(cli, name, param):
    n, seed = 2000, 11
    dumped = _floats(cli("warp", name, "--dump", n, "--seed", seed, *_param_args(param)).stdout)
    ours = penumbra.warp(name, penumbra.random_points(n, seed), param=param)
    assert ours.dtype == np.float32 and ours.shape[0] == n
    text = "\n".join(" ".join(f"{x:.9g}" for x in row) for row in ours.astype(np.float64))
    # %.9g round-trips float32: the same floats.
    assert np.array_equal(ours, dumped[:, :ours.shape[1]].astype(np.float32)), text[:200]
    if ours.shape[1] == 2:
        assert not dumped[:, 2].any()
    pdfs_cli = _floats(cli("warp", name, "--pdf", *_param_args(param), stdin=
                           "\n".join(" ".join(f"{x:.9g}" for x in row) for row in dumped)).stdout)[:, 0]
    ours_pdf = penumbra.pdf(name, dumped, param=param)
    assert np.array_equal(ours_pdf, pdfs_cli.astype(np.float32))
    assert np.all(ours_pdf >= 0) and np.all(np.isfinite(ours_pdf))


def test_pdf_of_a_different_parameter_differs():
    v = penumbra.warp("uniform-cone", penumbra.random_points(100, 3), param=0.9)
    assert not np.array_equal(penumbra.pdf("uniform-cone", v, param=0.9), penumbra.pdf("uniform-cone", v, param=0.5))


def _cli_chi2(cli, name, param, samples, seed, res, extra=()):
    out = cli("warp", name, "--samples", samples, "--seed", seed, "--res", res, *_param_args(param), *extra,
              check=False).stdout
    fields = {line.split()[0]: line.split()[1] for line in out.splitlines() if line.strip()}
    return float(fields["chi2"]), int(fields["dof"]), float(fields["p-value"]), fields["verdict"]


@pytest.mark.parametrize("name,param", CASES)
def test_chi2_matches_cli(cli, name, param):
    samples, seed, res = 200000, 5, 21
    chi2, dof, p, verdict = _cli_chi2(cli, name, param, samples, seed, res)
    r = penumbra.chi2_test(name, samples=samples, seed=seed, res=res, param=param)
    assert r.verdict == verdict == "accept"
    assert r.dof == dof and round(r.chi2, 2) == chi2
    assert f"{r.p_value:.4g}" == f"{p:.4g}"


def test_chi2_rejects_what_the_cli_rejects(cli):
    # A pdf that does not match the samples: the CLI and the module agree on the verdict and its numbers.
    out = cli("warp", "cosine-hemisphere", "--mismatch", "--samples", 20000, "--seed", 1, "--res", 10,
              check=False).stdout
    assert "REJECT" in out
    chi2, dof, p, verdict = _cli_chi2(cli, "tent", None, 100, 1, 200)
    r = penumbra.chi2_test("tent", samples=100, seed=1, res=200)
    assert r.verdict == verdict == "inconclusive" and r.dof == dof and round(r.chi2, 2) == chi2


def test_chi2_with_too_few_samples_is_inconclusive_not_rejected():
    # 100 samples over 2000 x 1000 cells: every cell expects 5e-5 samples, so after pooling no two cells
    # remain to compare. The test cannot decide (the warp is correct).
    start = time.monotonic()
    r = penumbra.chi2_test("cosine-hemisphere", samples=100, res=1000)
    seconds = time.monotonic() - start
    assert r.verdict == "inconclusive" and r.inconclusive and not r.accepted
    assert r.dof == 0 and math.isnan(r.p_value) and "too few samples" in r.message
    assert r.observed.sum() == 100 and r.expected.sum() + 0 == pytest.approx(100, rel=1e-4)
    # A bound on hangs, not a benchmark: integrating every one of the 2e6 cells took 18 s; the cells of
    # blocks that can only be pooled are not integrated one by one.
    assert seconds < 10, f"{seconds:.1f} s for 100 samples"
    # Enough samples for the same grid: a real verdict.
    r = penumbra.chi2_test("cosine-hemisphere", samples=20000, res=5)
    assert r.verdict == "accept" and not r.inconclusive and r.dof > 0


def test_warp_arguments_are_checked():
    u = np.zeros((4, 2))
    with pytest.raises(ValueError, match="name"):
        penumbra.warp("nope", u)
    with pytest.raises(ValueError, match="param"):
        penumbra.warp("tent", u, param=0.3)
    with pytest.raises(ValueError, match="param"):
        penumbra.warp("uniform-cone", u, param=1.5)
    with pytest.raises(ValueError, match="u"):
        penumbra.warp("tent", np.zeros((4, 3)))
    with pytest.raises(TypeError, match="u"):
        penumbra.warp("tent", "not an array")
    with pytest.raises(ValueError, match="v"):
        penumbra.pdf("tent", np.zeros(4))
    with pytest.raises(ValueError, match="samples"):
        penumbra.chi2_test("tent", samples=1)


def test_sample_points():
    for row in penumbra.samplers():
        pts = penumbra.sample_points(row["name"], 64, pixel=(3, 4), seed=2)
        assert pts.shape == (64, 2) and pts.dtype == np.float32
        assert np.all((pts >= 0) & (pts < 1))
        assert np.array_equal(pts, penumbra.sample_points(row["name"], 64, pixel=(3, 4), seed=2))
        assert not np.array_equal(pts, penumbra.sample_points(row["name"], 64, pixel=(3, 5), seed=2))
        assert not np.array_equal(pts, penumbra.sample_points(row["name"], 64, pixel=(3, 4), dims=(2, 3), seed=2))
    # 64 stratified points: one in each cell of the 8 x 8 grid.
    pts = penumbra.sample_points("stratified", 64, pixel=(1, 1))
    cells = {(int(x * 8), int(y * 8)) for x, y in pts}
    assert len(cells) == 64
    with pytest.raises(ValueError, match="sampler"):
        penumbra.sample_points("nope", 4)
    with pytest.raises(ValueError, match="dims"):
        penumbra.sample_points("independent", 4, dims=(1, 2))


@pytest.mark.parametrize("name", ["tent", "uniform-sphere"])
def test_warp_out_may_overlap_the_input(name):
    # NumPy's rule for ufuncs: the result is as if the input had been copied first.
    u = penumbra.random_points(1000, seed=5)
    expected = penumbra.warp(name, u)
    cols = expected.shape[1]
    flat = np.zeros(1000 + 1000 * cols, np.float32)
    u_alias = flat[:2000].reshape(1000, 2)
    u_alias[:] = u
    out = flat[1000:].reshape(1000, cols)  # starts inside u: each point written lands on points not yet read
    assert np.may_share_memory(u_alias, out)
    assert penumbra.warp(name, u_alias, out=out) is out
    assert np.array_equal(out, expected)
    if cols == 2:
        same = u.copy()
        assert penumbra.warp(name, same, out=same) is same  # in place
        assert np.array_equal(same, expected)


def test_pdf_out_may_overlap_the_input():
    v = penumbra.warp("uniform-hemisphere", penumbra.random_points(500, seed=6))
    expected = penumbra.pdf("cosine-hemisphere", v)
    flat = np.zeros(1500, np.float32)
    flat[:] = v.ravel()
    out = flat[1000:]  # the last third of v's own bytes: written before the points there are read
    assert penumbra.pdf("cosine-hemisphere", flat.reshape(500, 3), out=out) is out
    assert np.array_equal(out, expected)


def test_out_arrays_are_filled_and_checked():
    u = penumbra.random_points(100, seed=4)
    out = np.empty((100, 3), np.float32)
    assert penumbra.warp("uniform-sphere", u, out=out) is out
    assert np.array_equal(out, penumbra.warp("uniform-sphere", u))
    pdf_out = np.empty(100, np.float32)
    assert penumbra.pdf("uniform-sphere", out, out=pdf_out) is pdf_out
    assert np.allclose(pdf_out, 1 / (4 * np.pi))
    with pytest.raises(ValueError, match="out"):
        penumbra.warp("uniform-sphere", u, out=np.empty((100, 2), np.float32))
    with pytest.raises(TypeError, match="out"):
        penumbra.warp("uniform-sphere", u, out=np.empty((100, 3), np.float64))


BSDF_CASES = [("microfacet", dict(alpha=0.2, kd=0.3, incident=45.0), ["--kd", 0.3]),
              ("roughconductor", dict(alpha=0.3, distribution="ggx", incident=60.0), ["--distribution", "ggx"]),
              ("roughconductor", dict(alpha=0.05, incident=10.0), [])]


def _bsdf_args(kwargs, extra):
    return ["--param", kwargs["alpha"], "--incident", kwargs["incident"], *extra]


@pytest.mark.parametrize("name,kwargs,extra", BSDF_CASES)
def test_bsdf_sample_and_pdf_match_cli(cli, name, kwargs, extra):
    n, seed = 2000, 7
    dumped = _floats(cli("warp", name, "--dump", n, "--seed", seed, *_bsdf_args(kwargs, extra)).stdout)
    ours = penumbra.bsdf_sample(name, penumbra.random_points(n, seed), **kwargs)
    assert ours.dtype == np.float32 and ours.shape == (n, 3)
    assert np.array_equal(ours, dumped.astype(np.float32))
    rejected = ~ours.any(axis=1)  # (0, 0, 0): a draw below the surface
    assert np.all(ours[~rejected, 2] > 0)
    pdfs_cli = _floats(cli("warp", name, "--pdf", *_bsdf_args(kwargs, extra), stdin=
                           "\n".join(" ".join(f"{x:.9g}" for x in row) for row in dumped)).stdout)[:, 0]
    ours_pdf = penumbra.bsdf_pdf(name, dumped, **kwargs)
    assert np.array_equal(ours_pdf, pdfs_cli.astype(np.float32))
    assert np.all(ours_pdf[~rejected] > 0) and np.all(np.isfinite(ours_pdf))


@pytest.mark.parametrize("name,kwargs,extra", BSDF_CASES)
def test_bsdf_chi2_matches_cli(cli, name, kwargs, extra):
    samples, seed, res = 200000, 5, 21
    out = cli("warp", name, "--samples", samples, "--seed", seed, "--res", res, *_bsdf_args(kwargs, extra),
              check=False).stdout
    fields = {line.split()[0]: line.split()[1] for line in out.splitlines() if line.strip()}
    r = penumbra.bsdf_chi2_test(name, samples=samples, seed=seed, res=res, **kwargs)
    assert r.verdict == fields["verdict"] == "accept"
    assert r.dof == int(fields["dof"]) and round(r.chi2, 2) == float(fields["chi2"])
    assert r.rejected == float(fields["rejected"])
    assert r.rejected >= 0 and r.expected_rejected >= 0


def test_bsdf_arguments_are_checked_and_named():
    u = penumbra.random_points(4, 1)
    for kwargs, word in [(dict(alpha=0.0), "alpha 0"), (dict(alpha=float("nan")), "alpha nan"),
                         (dict(incident=95.0), "incident 95"), (dict(kd=1.5), "kd 1.5"),
                         (dict(int_ior=0.0), "int_ior 0")]:
        with pytest.raises(ValueError, match=word):
            penumbra.bsdf_sample("microfacet", u, **kwargs)
    with pytest.raises(ValueError, match="distribution phong"):
        penumbra.bsdf_pdf("roughconductor", np.zeros((1, 3)), distribution="phong")
    with pytest.raises(ValueError, match="unknown BSDF"):
        penumbra.bsdf_chi2_test("diffuse")
    with pytest.raises(ValueError, match="shape"):
        penumbra.bsdf_pdf("microfacet", np.zeros((3, 2)))
    assert penumbra.bsdf_names() == ["microfacet", "roughconductor"]
