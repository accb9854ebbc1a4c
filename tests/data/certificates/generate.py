"""Regenerate the known-good/known-bad certificate files of this folder.

Run from the repository root: ``PYTHONPATH=. python tests/data/certificates/generate.py``.
``valid/`` files must be accepted by ``proofs_check`` (exit 0), ``invalid/`` ones rejected
(exit 1) and ``malformed/`` ones refused (exit 2); ``tests/proofs_check/`` asserts
exactly that. Every bad file is a good one with one deliberate defect, named by the file.
"""

from __future__ import annotations

import copy
import json
from fractions import Fraction
from math import isqrt
from pathlib import Path

import numpy as np

from theory.consensus.certificates import (
    exact_gain_certificate,
    mjls_stability_certificate,
    s_detectability_certificate,
)
from theory.consensus.design import self_weight_design
from theory.consensus.infeasibility import infeasibility_certificate
from theory.consensus.s_detectability import decide_s_detectability, s_detectability_witness
from theory.core.certificate_format import bundle
from theory.core.exact import dyadic_matrix, fraction_strings, rational_matrix
from theory.kinds import load_case
from theory.pursuit.certificates import (
    box_witness,
    iss_box_certificate,
    iss_certificate,
    loop_bounds,
)
from theory.registry import case_certificates
from theory.tdoa.design import tdoa_redundancy
from theory.tdoa.estimation.stability import (
    covariance_bound_certificate,
    ekf_covariance_bound_certificate,
)
from theory.tdoa.geometry.margin import tdoa_margin
from theory.tdoa.observability.certificates import generic_rank_certificates

HERE = Path(__file__).resolve().parent


def _fixed_point(step, start, iterations=3000):
    value = start
    for _ in range(iterations):
        value = step(value)
    return value


def _lyapunov_L(gammas, W):
    n = gammas[0].shape[0]
    return _fixed_point(
        lambda P: [
            np.eye(n) + g @ np.tensordot(w, np.array(P), 1) @ g.T
            for g, w in zip(gammas, W, strict=True)
        ],
        [np.eye(n)] * len(gammas),
    )


def _lyapunov_J(modes, W):
    n = modes[0][0].shape[0]

    def step(X):
        out = [np.eye(n) for _ in X]
        for M in modes:
            moved = np.array([m @ x @ m.T for m, x in zip(M, X, strict=True)])
            out = [o + np.tensordot(w, moved, 1) for o, w in zip(out, W, strict=True)]
        return out

    return _fixed_point(step, [np.eye(n)] * len(W))


def _example1(w11):
    A = 2 * np.eye(2)
    Cs = [np.array([[1.0, 0]]), np.array([[0.0, 1]]), np.eye(2)]
    W = np.array([[w11, 1 - w11, 0], [1 - w11, w11, 0], [0, 0, 1]])
    gains = [np.array([[2.0], [0]]), np.array([[0.0], [2]]), 2 * np.eye(2)]
    return A, Cs, W, gains


def good() -> dict[str, dict]:
    scalar = {
        "format": "trackcert-certificate/1",
        "kind": "mjls-stability",
        "source": "seed 000, Lemma 5.2.2",
        "claim": {"statement": "r_σ(L) < 1", "spectral_radius_below": "1"},
        "data": {"W": [["1/2", "1/2"], ["1/4", "3/4"]], "Gamma": [[["1/2"]], [["-1/3"]]]},
        "witness": {"operator": "L", "P": [[["1"]], [["1"]]], "decrease": [[["3/4"]], [["8/9"]]]},
    }
    rng = np.random.default_rng(5)
    gammas = [0.4 * rng.standard_normal((3, 3)) for _ in range(3)]
    W = np.array([[0.5, 0.25, 0.25], [0.2, 0.8, 0], [0, 0.3, 0.7]])
    P = _lyapunov_L(gammas, W)
    A, Cs, Wg, gains = _example1(0.24)
    modes = [[0.5 * rng.standard_normal((2, 2)) for _ in range(3)] for _ in range(2)]
    A_ekf = np.array([[1.0, 0.5], [0.0, 1.0]])
    Hs = [[np.eye(2) + 0.3 * rng.standard_normal((2, 2)) for _ in range(3)]]
    Ks = [[0.7 * np.linalg.inv(h) + 0.05 * rng.standard_normal((2, 2)) for h in Hs[0]]]
    ekf_modes = [[A_ekf @ (np.eye(2) - k @ h) for k, h in zip(Ks[0], Hs[0], strict=True)]]
    cases = HERE.parents[2] / "cases"
    case = load_case(cases / "fig43-case-d.yaml")
    split = load_case(cases / "seed002-fig32-split.yaml")
    example2 = load_case(cases / "ch5-example-2-wg.yaml").spec
    lmi = s_detectability_witness(example2.A, example2.C, example2.W)
    return {
        "mjls-stability-scalar": scalar,
        "mjls-stability-three-agents": mjls_stability_certificate(gammas, W, P),
        "mjls-stability-rate-bound": mjls_stability_certificate(
            gammas, W, P, spectral_radius_below=0.9
        ),
        "s-detectability-ch5-example1-Wg": s_detectability_certificate(
            A,
            Cs,
            Wg,
            "consensus-then-filter",
            gains,
            _lyapunov_L([A - g @ c for g, c in zip(gains, Cs, strict=True)], Wg),
        ),
        "covariance-bound-two-modes": covariance_bound_certificate(W, modes, _lyapunov_J(modes, W)),
        "covariance-bound-ekf-gains": ekf_covariance_bound_certificate(
            A_ekf, Ks, Hs, W, _lyapunov_J(ekf_modes, W)
        ),
        "s-detectability-ch5-example2-Wg-lmi": bundle(
            case_certificates(load_case(cases / "ch5-example-2-wg.yaml"))
        ),
        "s-detectability-ch5-example2-Wg-dual": s_detectability_certificate(
            example2.A,
            example2.C,
            example2.W,
            example2.order,
            lmi["gains"],
            list(lmi["Y"]),
            dual=True,
        ),
        **_boundary(),
        **_radius_kinds(),
        **_tdoa_design(),
        "generic-rank-fig43-case-d": bundle(generic_rank_certificates(case.spec, case=case.name)),
        "generic-rank-seed002-fig32-split-agent4": generic_rank_certificates(
            split.spec, case=split.name
        )[4],
        **{
            f"iss-{name}": iss_certificate(load_case(cases / f"{name}.yaml").spec, case=name)
            for name in ("pursuit-table1-n3", "pursuit-table2-n1")
        },
        "iss-box-pursuit-table1-n3": _iss_box(),
        **_self_weight(),
    }


def _iss_box() -> dict:
    """Table I, N = 3, for every k_γ ∈ [1/10, 10], k_c ∈ [1/10, 1], K_p scale ∈ [1, 2] and
    ε₁ ∈ [−1, −1/4] (kind iss-box): λ = 1/10 = k_γ,lo, k̄_p ≥ 4/5, α = a/10."""
    name = "pursuit-table1-n3"
    bounds = loop_bounds(load_case(HERE.parents[2] / "cases" / f"{name}.yaml").spec)
    box = {
        "K_p_scale": (Fraction(1), Fraction(2)),
        "epsilon_1": (Fraction(-1), Fraction(-1, 4)),
        "k_gamma": (Fraction(1, 10), Fraction(10)),
        "k_c": (Fraction(1, 10), Fraction(1)),
    }
    return iss_box_certificate(bounds, box, box_witness(bounds, box), case=name)


def _boundary() -> dict[str, dict]:
    """Seed 000 Example 1 at the self-weight bound 0.25: just below it (w = 0.249999999, exact
    Lyapunov tuple of the gains [2; 0], [0; 2], 2I: P_1 ≈ diag(1, 1e9)), on it and above it (exact
    Farkas multipliers of the blind agent 2), and Example 2's W_b (blind agent 3, λ = 1.7205)."""
    A, Cs, W, gains = _example1(0.249999999)
    exact = [rational_matrix(g) for g in gains]
    example2 = load_case(HERE.parents[2] / "cases" / "ch5-example-2-wb.yaml").spec
    return {
        "s-detectability-ch5-example1-w0.249999999-exact": exact_gain_certificate(
            A, Cs, W, exact, order="consensus-then-filter"
        ),
        "s-detectability-infeasible-ch5-example1-Wc": infeasibility_certificate(
            *_example1(0.25)[:3]
        ),
        "s-detectability-infeasible-ch5-example1-Wb": infeasibility_certificate(
            *_example1(0.26)[:3]
        ),
        "s-detectability-infeasible-ch5-example2-Wb": infeasibility_certificate(
            example2.A, example2.C, example2.W
        ),
    }


def _forged_example1() -> dict:
    """Issue 23's forgery: seed 000 Example 1 at w₁₁ = w₂₂ = 0.3 (not S-detectable), zero gains,
    P = I and ρ = 5. Its inequalities hold (5P_i − L_i(P) = 5I − 4I), so r_σ(L) < 5 is proved:
    valid as ``gains-radius-below``, refused as ``s-detectability``."""
    eye = [["1", "0"], ["0", "1"]]
    return {
        "format": "trackcert-certificate/1",
        "kind": "gains-radius-below",
        "source": "issue 23 (forged S-detectability certificate)",
        "claim": {"statement": "r_σ(L) < 5 with zero gains", "spectral_radius_below": "5"},
        "data": {
            "A": [["2", "0"], ["0", "2"]],
            "C": [[["1", "0"]], [["0", "1"]], eye],
            "W": [["3/10", "7/10", "0"], ["7/10", "3/10", "0"], ["0", "0", "1"]],
        },
        "witness": {
            "operator": "L",
            "gains": [[["0"], ["0"]], [["0"], ["0"]], [["0", "0"], ["0", "0"]]],
            "P": [eye, eye, eye],
            "decrease": [eye, eye, eye],
        },
    }


def _radius_kinds() -> dict[str, dict]:
    """The kinds for any ρ: the forgery above, and Example 1 at w = 0.24 (S-detectable) where
    no gains give r_σ(L) < 0.96 = λ² w₁₁ (exact multipliers of the blind agent 1)."""
    return {
        "gains-radius-below-ch5-example1-w0.3-zero-gains": _forged_example1(),
        "gains-radius-below-infeasible-ch5-example1-w0.24-rho0.96": infeasibility_certificate(
            *_example1(0.24)[:3], rho=Fraction(24, 25)
        ),
    }


def _float_dual(w11: float) -> dict:
    """The solver's multipliers for Example 1 at ``w11``, rounded: the "ε_cert ≈ 9e-9"
    evidence that used to refute S-detectability at w = 0.249999999. ``F*(Λ, Ψ) ≠ 0``."""
    A, Cs, W, _ = _example1(w11)
    decision = decide_s_detectability(A, Cs, W)
    cert = copy.deepcopy(infeasibility_certificate(*_example1(0.25)[:3]))
    cert["data"]["W"] = fraction_strings([[Fraction(repr(x)) for x in row] for row in W.tolist()])
    cert["witness"] = {
        name: [fraction_strings(dyadic_matrix(m, 40)) for m in decision.multipliers[key]]
        for name, key in (("Lambda", "Lambda"), ("Psi", "Psi"))
    }
    return cert


def bad(valid: dict[str, dict]) -> tuple[dict[str, dict], dict[str, object]]:
    invalid, malformed = {}, {}
    c = copy.deepcopy(valid["s-detectability-infeasible-ch5-example1-Wc"])
    c["data"]["W"] = [["6/25", "19/25", "0"], ["19/25", "6/25", "0"], ["0", "0", "1"]]
    invalid["s-detectability-infeasible-Wc-multipliers-for-Wg"] = c
    c = copy.deepcopy(valid["s-detectability-infeasible-ch5-example1-Wc"])
    c["witness"]["Psi"][1] = [
        [x if x.startswith("-") or x == "0" else "-" + x for x in row]
        for row in c["witness"]["Psi"][1]
    ]
    invalid["s-detectability-infeasible-negated-Psi"] = c
    c = copy.deepcopy(valid["s-detectability-infeasible-ch5-example1-Wc"])
    c["witness"] = {k: [[["0"] * len(r) for r in m] for m in v] for k, v in c["witness"].items()}
    invalid["s-detectability-infeasible-zero-multipliers"] = c
    invalid["s-detectability-infeasible-float-dual-w0.249999999"] = _float_dual(0.249999999)
    c = copy.deepcopy(valid["mjls-stability-scalar"])
    c["witness"]["P"][0] = [["-1"]]
    c["witness"]["decrease"][0] = [["-5/4"]]
    c["witness"]["decrease"][1] = [["7/18"]]
    invalid["mjls-not-positive-definite"] = c
    c = copy.deepcopy(valid["mjls-stability-scalar"])
    c["witness"]["decrease"][1] = [["1"]]
    invalid["mjls-decrease-misstated"] = c
    c = copy.deepcopy(valid["mjls-stability-scalar"])
    c["data"]["W"][0] = ["3/2", "-1/2"]
    c["witness"]["decrease"][0] = [["3/4"]]
    invalid["mjls-negative-weight"] = c
    c = copy.deepcopy(valid["mjls-stability-three-agents"])
    c["witness"]["P"][0], c["witness"]["P"][1] = c["witness"]["P"][1], c["witness"]["P"][0]
    invalid["mjls-two-agents-swapped"] = c
    c = copy.deepcopy(valid["mjls-stability-three-agents"])
    c["witness"]["P"][2][0][1] = str(json.loads(json.dumps(c["witness"]["P"][2][0][1])) + "1")
    invalid["mjls-asymmetric-P"] = c
    c = copy.deepcopy(valid["s-detectability-ch5-example1-Wg"])
    c["data"]["W"] = [["1/4", "3/4", "0"], ["3/4", "1/4", "0"], ["0", "0", "1"]]
    invalid["s-detectability-ch5-example1-Wc-altered-data"] = c
    c = copy.deepcopy(valid["covariance-bound-two-modes"])
    c["data"]["modes"][1]["M"][0][0][0] = "3"
    invalid["covariance-bound-altered-mode"] = c
    g = valid["generic-rank-fig43-case-d"]
    c = copy.deepcopy(g)
    c["certificates"][1]["witness"]["minor"] = "1"
    invalid["generic-rank-stated-minor-wrong"] = c
    c = copy.deepcopy(g)
    c["certificates"][0]["witness"]["directions"][0][0] = "1/2"
    invalid["generic-rank-direction-not-unit"] = c
    c = copy.deepcopy(g["certificates"][1])
    c["witness"]["rows"] = [1, 2, 3, 4, 5, 6]
    c["witness"]["minor"] = "0"
    invalid["generic-rank-singular-minor"] = c
    malformed |= _claims_beyond_the_kind(valid)
    c = copy.deepcopy(valid["mjls-stability-scalar"])
    c["format"] = "trackcert-certificate/2"
    malformed["wrong-format-version"] = c
    malformed["truncated"] = json.dumps(valid["mjls-stability-scalar"])[:-20]
    malformed["json-float"] = json.dumps(valid["mjls-stability-scalar"]).replace('"3/4"', "0.75")
    c = copy.deepcopy(valid["mjls-stability-three-agents"])
    del c["witness"]["P"][2]
    malformed["dropped-block"] = c
    c = copy.deepcopy(valid["mjls-stability-scalar"])
    c["data"]["Gamma"][1] = [["1", "0"], ["0", "1"]]
    malformed["shape-mismatch"] = c
    c = copy.deepcopy(valid["mjls-stability-scalar"])
    c["witness"]["P"][0] = [["1/0"]]
    malformed["zero-denominator"] = c
    invalid["iss-lambda-doubled"] = _iss_changed(valid["iss-pursuit-table1-n3"], "lambda", 2)
    invalid["iss-a-above-connectivity"] = _iss_changed(
        valid["iss-pursuit-table1-n3"], "a", Fraction(11, 10)
    )
    invalid["iss-kp-bar-below-norm"] = _iss_changed(
        valid["iss-pursuit-table2-n1"], "kp_bar", Fraction(9, 10)
    )
    c = copy.deepcopy(valid["iss-pursuit-table1-n3"])
    c["witness"]["kappa"] = "-" + c["witness"]["kappa"]
    invalid["iss-negative-kappa"] = c
    invalid["iss-negative-radius-mu-r-understated"] = _negative_radius(
        valid["iss-pursuit-table1-n3"]
    )
    c = copy.deepcopy(valid["iss-pursuit-table1-n3"])
    del c["witness"]["r"]
    malformed["iss-dropped-left-eigenvector"] = c
    c = copy.deepcopy(valid["iss-box-pursuit-table1-n3"])
    c["claim"]["box"]["epsilon_1"] = ["-1", "0"]
    invalid["iss-box-epsilon-interval-reaches-zero"] = c
    c = copy.deepcopy(valid["iss-box-pursuit-table1-n3"])
    c["claim"]["box"]["k_gamma"] = ["1/20", "10"]
    invalid["iss-box-k-gamma-below-lambda"] = c
    c = copy.deepcopy(valid["iss-box-pursuit-table1-n3"])
    c["claim"]["box"]["k_c"] = ["1", "1/10"]
    malformed["iss-box-empty-interval"] = c
    malformed["nested-bundle"] = bundle([bundle([valid["mjls-stability-scalar"]])])
    _tdoa_design_defects(valid, invalid, malformed)
    _self_weight_defects(valid, invalid, malformed)
    return invalid, malformed


def _tdoa_design() -> dict[str, dict]:
    """A displacement margin (witness ρ̄ ≈ 1.33 above it) and a loss tolerance (docs/design.md)."""
    cases = HERE.parents[2] / "cases"
    margin = tdoa_margin(load_case(cases / "fig43-case-a.yaml"), search=False)
    ring = load_case(cases / "seed000-sec44-ring.yaml")
    return {
        "tdoa-observability-margin-fig43-case-a": margin.certificates[0],
        "tdoa-loss-tolerance-seed000-sec44-ring-links": tdoa_redundancy(
            ring, links=True
        ).certificates[0],
    }


def _tdoa_design_defects(valid: dict, invalid: dict, malformed: dict) -> None:
    """A radius past the witness (3/2 > ρ̄ ≈ 1.33: false), fewer_than = 3 on the ring (removing
    two links isolates an agent: false), a zero radius (refused)."""
    c = copy.deepcopy(valid["tdoa-observability-margin-fig43-case-a"])
    c["claim"]["radius"] = "3/2"
    invalid["tdoa-observability-margin-radius-past-witness"] = c
    c = copy.deepcopy(valid["tdoa-loss-tolerance-seed000-sec44-ring-links"])
    c["claim"]["fewer_than"] = 3
    invalid["tdoa-loss-tolerance-ring-fewer-than-3"] = c
    c = copy.deepcopy(valid["tdoa-observability-margin-fig43-case-a"])
    c["claim"]["radius"] = "0"
    malformed["tdoa-observability-margin-zero-radius"] = c


def _self_weight() -> dict[str, dict]:
    """Thm 5.2.10 (2) for every w ≥ u: agent 1 of the hand-written complex-root case (u = 1/2,
    the pair 1 ± i) and of the irrational real case (u = 3 − 2√2), ``design self-weight``."""
    folder = HERE.parent / "dkf"
    return {
        f"self-weight-necessary-violated-{name}": self_weight_design(
            load_case(folder / f"self-weight-{name}.yaml"), agents=[0]
        ).at_or_above.certificate
        for name in ("complex-root", "irrational-real")
    }


def _self_weight_defects(valid: dict, invalid: dict, malformed: dict) -> None:
    """u = 1/2 − 10⁻⁹ claimed exact (below the threshold: false), an interval around the other
    root 3 + 2√2 of u² − 6u + 1 (isolating, but not the threshold: false), u = "2/4" (refused)."""
    c = copy.deepcopy(valid["self-weight-necessary-violated-complex-root"])
    c["claim"]["threshold"] = "499999999/1000000000"
    c["witness"]["below"] = "249999999/500000000"
    invalid["self-weight-necessary-violated-threshold-below"] = c
    c = copy.deepcopy(valid["self-weight-necessary-violated-irrational-real"])
    c["claim"]["threshold_interval"] = ["5", "6"]
    invalid["self-weight-necessary-violated-other-root"] = c
    c = copy.deepcopy(valid["self-weight-necessary-violated-complex-root"])
    c["claim"]["threshold"] = "2/4"
    malformed["self-weight-necessary-violated-non-canonical-threshold"] = c


def _claims_beyond_the_kind(valid: dict[str, dict]) -> dict[str, dict]:
    """Certificates whose claimed numbers fall outside their kind's range, or are not canonical.

    Each keeps inequalities that hold: only the kind's claim (or the spelling) is wrong."""
    out = {}
    c = copy.deepcopy(valid["gains-radius-below-ch5-example1-w0.3-zero-gains"])
    c["kind"] = "s-detectability"
    c["claim"]["statement"] = "(A, C, W) is S-detectable"
    out["s-detectability-forged-rho5-ch5-example1-w0.3"] = c
    c = copy.deepcopy(valid["gains-radius-below-infeasible-ch5-example1-w0.24-rho0.96"])
    c["kind"] = "s-detectability-infeasible"
    c["claim"]["statement"] = "(A, C, W) is not S-detectable"
    out["s-detectability-infeasible-rho0.96-ch5-example1-w0.24"] = c
    for name, path, text in (
        ("two-halves", ("claim", "spectral_radius_below"), "2/2"),
        ("four-halves", ("data", "A", 0, 0), "4/2"),
        ("negative-zero", ("data", "A", 0, 1), "-0"),
    ):
        c = copy.deepcopy(valid["s-detectability-ch5-example1-Wg"])
        node = c
        for key in path[:-1]:
            node = node[key]
        assert Fraction(node[path[-1]]) == Fraction(text)
        node[path[-1]] = text
        out[f"non-canonical-{name}"] = c
    c = copy.deepcopy(valid["generic-rank-fig43-case-d"])
    c["certificates"][0]["data"]["T"] = "0"
    out["generic-rank-zero-sampling-period"] = c
    return out


def _negative_radius(cert: dict) -> dict:
    """r_x = −30, r_y = 1: sup‖r′‖² = 900, but max(r_x, r_y)² = 1. With μ_r = 1 and s shrunk to
    √(k̄_p² + 2) (rounded up), every check of the old rule passes and the gain is too small."""
    c = copy.deepcopy(cert)
    for path in c["data"]["paths"]:
        path["r_x"], path["r_y"] = "-30", "1"
    w = {k: Fraction(v) for k, v in c["witness"].items() if k != "r"}
    scale = 10**9
    w["mu_r"] = Fraction(1)
    w["s"] = Fraction(isqrt(int((w["kp_bar"] ** 2 + 2) * scale**2)) + 1, scale)
    w["g_e"] = w["s"] / w["lambda"]
    w["gain"] = w["g_e"] * (1 + w["g_xi"])
    c["witness"] |= {k: str(v) for k, v in w.items()}
    return c


def _iss_changed(cert: dict, key: str, factor) -> dict:
    """``cert`` with one witness bound scaled and the derived constants recomputed, so that only
    the inequality of that bound fails (E2 for ``lambda``, E3 for ``kp_bar``, C3 for ``a``)."""
    c = copy.deepcopy(cert)
    w = {k: Fraction(v) if isinstance(v, str) else v for k, v in c["witness"].items()}
    w[key] *= factor
    w["g_e"] = w["s"] / w["lambda"]
    w["gain"] = w["g_e"]
    if "a" in w:
        w["alpha"] = Fraction(c["data"]["k_c"]) * w["a"]
        w["g_xi"] = w["b"] / (w["rho"] * w["alpha"])
        w["gain"] = w["g_e"] * (1 + w["g_xi"])
    c["witness"] = {k: v if isinstance(v, list) else str(v) for k, v in w.items()}
    return c


def main() -> None:
    valid = good()
    invalid, malformed = bad(valid)
    for folder, items in (("valid", valid), ("invalid", invalid), ("malformed", malformed)):
        (HERE / folder).mkdir(exist_ok=True)
        for name, content in items.items():
            text = (
                content
                if isinstance(content, str)
                else json.dumps(content, indent=1, ensure_ascii=False)
            )
            (HERE / folder / f"{name}.json").write_text(text + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
