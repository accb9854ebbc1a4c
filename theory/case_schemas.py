"""Each case kind's schema (:class:`theory.core.schema.KindSchema`): field, meaning, unit, default,
built on the loader's key tuples of the kind's ``case`` module so the two cannot drift.

``trackcert schema KIND`` prints one as JSON Schema; ``--write-docs docs`` writes
``docs/cases/<kind>.md`` and ``docs/schema/<kind>.json`` from it.
"""

from __future__ import annotations

from collections.abc import Callable

from theory.core.errors import COMMAND_LINE, CaseError
from theory.core.schema import (
    BOOL,
    MATRIX,
    NUMBER,
    POSITIVE,
    VECTOR,
    Field,
    KindSchema,
    block,
    choice,
    list_of,
    mapping_of,
    nullable,
    one_of,
    tolerance_fields,
)

__all__ = ["SCHEMAS", "kind_schema"]

INFINITY = {"enum": ["inf", ".inf", "infinity"]}  # YAML's .inf is a number; these are strings
INF = {"anyOf": [POSITIVE, INFINITY]}
THRESHOLD = {"anyOf": [{"type": "number", "minimum": 0}, INFINITY]}
EDGES = list_of(
    {"type": "array", "items": {"type": "integer", "minimum": 1}, "minItems": 2, "maxItems": 2}
)
PER_AGENT_BOOLS = list_of(BOOL)
NODE_ID = {"type": "integer", "minimum": 1}
WEIGHTED_EDGES = list_of(
    one_of(
        EDGES["items"],
        {
            "type": "array",
            "prefixItems": [NODE_ID, NODE_ID, POSITIVE],
            "items": POSITIVE,
            "minItems": 3,
            "maxItems": 3,
        },
    )
)


def _tdoa() -> KindSchema:
    """seed 000 ch. 4 eqs. (4.1)–(4.10): a scene of agents, a target and a network."""
    from theory.tdoa.case import EXPECT_KEYS, FIELDS, TOLERANCE_KEYS, WeightRule

    rules = [r.value for r in WeightRule if r is not WeightRule.EXPLICIT]
    return KindSchema(
        "tdoa",
        "A TDOA scene: agents (fixed, or a trajectory), a target and their network; "
        "`trackcert topology` decides every agent's observability (seed 000 §4.2).",
        "seed 000 ch. 4, eqs. (4.1)–(4.10), §4.2.2; seed 001",
        block(
            FIELDS,
            Field("T", POSITIVE, "ping period", "s", required=True),
            Field("dim", {"enum": [2, 3]}, "space dimension", "", "inferred from the coordinates"),
            Field(
                "agents",
                one_of(MATRIX, list_of(MATRIX)),
                "agent positions, N × dim, or a trajectory steps × N × dim",
                "m",
                required=True,
            ),
            Field(
                "target",
                one_of(VECTOR, MATRIX),
                "target position (dim numbers), or a trajectory steps × dim",
                "m",
                required=True,
            ),
            Field(
                "edges",
                EDGES,
                "links as 1-based pairs [i, j] (with `directed`, i sends to j)",
                default="read off an explicit `weights` matrix",
            ),
            Field(
                "comm_range",
                POSITIVE,
                "distance rule: i and j linked when closer than comm_range (strict <), "
                "instead of `edges`",
                "m",
                "—",
            ),
            Field("directed", BOOL, "whether `edges` are one-way", default="false"),
            Field(
                "weights",
                one_of(choice(rules), MATRIX),
                "consensus weights: a rule, or an explicit N × N row-stochastic matrix",
                default="metropolis",
            ),
            where="tdoa",
        ),
        block(
            EXPECT_KEYS,
            Field("observable", PER_AGENT_BOOLS, "each agent observes the target alone"),
            Field(
                "heuristic_4_noncoplanar",
                PER_AGENT_BOOLS,
                "each agent has ≥ 4 non-coplanar agents in its neighbourhood (Thm 4.2.3 heuristic)",
            ),
            Field(
                "mirror_ambiguous",
                PER_AGENT_BOOLS,
                "each agent's TDOAs admit a second (mirror) position",
            ),
            Field(
                "network_rank",
                {"type": "integer", "minimum": 0},
                "rank of the networked observability matrix O",
            ),
            Field("network_observable", BOOL, "the networked pair (W ⊗ A, D_H) is observable"),
            Field("network_detectable", BOOL, "the networked pair is detectable (Cor. 4.2.4)"),
            Field(
                "first_failure_step",
                nullable({"type": "integer", "minimum": 0}),
                "first time step at which an agent is unobservable (null: none)",
            ),
            Field(
                "unobservable_steps",
                list_of({"type": "integer", "minimum": 0}),
                "per agent, the number of steps at which it is unobservable",
            ),
            where="tdoa expect",
        ),
        tolerance_fields(TOLERANCE_KEYS),
    )


def _tdoa_sim() -> KindSchema:
    """seed 000 §4.4: the closed loop of target, pings, filters and moving agents."""
    from theory.tdoa.case import SIM_FIELDS, TDOA_SIM, CovNorm, Filter, Linearize, WeightRule

    rules = [r.value for r in WeightRule if r is not WeightRule.EXPLICIT]
    vec3 = {**VECTOR, "minItems": 3, "maxItems": 3}
    cov = one_of(POSITIVE, MATRIX)
    return KindSchema(
        "tdoa-sim",
        "A closed-loop TDOA run of seed 000 §4.4: a moving target, pings every T, consensus "
        "every τ, agents that move when their covariance exceeds b; `trackcert simulate` runs it.",
        "seed 000 §4.4, eqs. (4.41)–(4.50)",
        block(
            SIM_FIELDS,
            Field("agents", MATRIX, "initial agent positions, N × 3", "m", required=True),
            Field("target", vec3, "initial target position", "m", required=True),
            Field("target_velocity", vec3, "initial target velocity", "m/s", "[0, 0, 0]"),
            Field(
                "Q", cov, "white-acceleration covariance: a number (· I₃) or 3 × 3", "m²/s³", "0.01"
            ),
            Field("R", POSITIVE, "TDOA noise variance r (R_i = r I)", "m²", "1.0"),
            Field("T", POSITIVE, "ping period", "s", "1.0"),
            Field("tau", POSITIVE, "consensus period; T/τ must be an integer", "s", "T"),
            Field("P0", cov, "initial covariance: a number (· I₆) or 6 × 6", "m², m²/s²", "100"),
            Field(
                "x0",
                {**VECTOR, "minItems": 6, "maxItems": 6},
                "every agent's initial estimate [p; ṗ]",
                "m, m/s",
                "[0, 0, 0, 0, 0, 0]",
            ),
            Field(
                "b",
                THRESHOLD,
                "movement threshold: an agent moves iff ‖P_i‖ > b (.inf: never)",
                "m²",
                "0",
            ),
            Field("edges", EDGES, "fixed undirected links, 1-based pairs", default="—"),
            Field(
                "comm_range",
                POSITIVE,
                "distance rule (re-evaluated every τ), instead of edges",
                "m",
                "—",
            ),
            Field(
                "weights",
                one_of(choice(rules), MATRIX),
                "consensus weights: a rule, or N × N (with edges only)",
                default="metropolis",
            ),
            Field(
                "filter",
                choice([f.value for f in Filter]),
                "the filter every agent runs",
                default=Filter.AVERAGED.value,
            ),
            Field(
                "linearize",
                choice([v.value for v in Linearize]),
                "where the Jacobians are taken: the estimate (EKF) or the truth",
                default=Linearize.ESTIMATE.value,
            ),
            Field(
                "steps",
                {"type": "integer", "minimum": 1},
                "number of pings after the first",
                default="100",
            ),
            Field(
                "formation",
                one_of(choice(["cube", "crown"]), MATRIX),
                "formation: cube, crown, or explicit N × 3 offsets d_i (eq. (4.45))",
                "m",
                "cube",
            ),
            Field(
                "formation_radius",
                POSITIVE,
                "circumradius of the cube / radius of the crown",
                "m",
                "10",
            ),
            Field("formation_height", POSITIVE, "half-height of the crown", "m", "5"),
            Field("pole", POSITIVE, "closed-loop pole −λ of the linearized agents", "1/s", "0.5"),
            Field(
                "max_input",
                {**list_of(POSITIVE), "minItems": 3, "maxItems": 3},
                "actuator limits |u₁|, |u₂|, |u₃| (.inf: none)",
                "m/s³, rad/s², rad/s²",
                "[2, 2, 2]",
            ),
            Field(
                "substeps",
                {"type": "integer", "minimum": 1},
                "Runge–Kutta steps per τ",
                default="2",
            ),
            Field(
                "cov_norm",
                choice([c.value for c in CovNorm]),
                "the norm ‖P_i‖ the movement trigger uses",
                default=CovNorm.SPECTRAL.value,
            ),
            where="tdoa-sim",
        ),
        block(
            TDOA_SIM.expect_keys,
            Field(
                "bounded_error",
                BOOL,
                "every agent's final localization error is below tolerances.error_bound",
            ),
            Field("max_final_error", POSITIVE, "largest final localization error, at most", "m"),
            where="tdoa-sim expect",
        ),
        tolerance_fields(
            TDOA_SIM.tolerance_keys,
            Field("error_bound", POSITIVE, "bound of `bounded_error`", "m", "—"),
        ),
    )


def _dkf() -> KindSchema:
    """seed 000 ch. 5 eqs. (5.1)–(5.4), App. C.3: a consensus Kalman filter."""
    from theory.consensus.case import EXPECT_KEYS, FIELDS, TOLERANCE_KEYS, Order

    per_agent = list_of(one_of(MATRIX, {"type": "array", "maxItems": 0}))
    return KindSchema(
        "dkf",
        "A linear system x⁺ = A x + w watched by N agents y_i = C_i x + v_i that run a consensus "
        "Kalman filter with weights W; `trackcert dkf` decides S-detectability and Thm 5.2.10's "
        "conditions.",
        "seed 000 ch. 5, eqs. (5.1)–(5.4), App. C.3",
        block(
            FIELDS,
            Field("A", MATRIX, "n × n system matrix (eq. (5.1))", required=True),
            Field(
                "C",
                per_agent,
                "one p_i × n measurement matrix per agent ([]: no sensor)",
                required=True,
            ),
            Field(
                "W",
                MATRIX,
                "N × N row-stochastic consensus weights, w_ii > 0 (eq. (5.3))",
                required=True,
            ),
            Field("Q", MATRIX, "n × n process-noise covariance, positive definite", required=True),
            Field(
                "R",
                per_agent,
                "one p_i × p_i measurement-noise covariance per agent, "
                "positive definite ([] with C_i = [])",
                required=True,
            ),
            Field(
                "L",
                per_agent,
                "fixed gains, one n × p_i matrix per agent (eq. (5.4))",
                default="the Kalman gains",
            ),
            Field(
                "order",
                choice([o.value for o in Order]),
                "consensus then filter (eqs. (5.3)–(5.4)) or filter then consensus (App. C.3)",
                default=Order.CONSENSUS_THEN_FILTER.value,
            ),
            where="dkf",
        ),
        block(
            EXPECT_KEYS,
            Field("s_detectable", BOOL, "the network is S-detectable (Def. 5.2.4, LMI)"),
            Field("spectral_radius_B", NUMBER, "spectral radius of B (eq. (5.20))"),
            Field("spectral_radius_L", NUMBER, "spectral radius of the operator L (eq. (5.13))"),
            Field("self_weight_ok", BOOL, "w_ii r² < 1 for every agent (Thm 5.2.10)"),
            Field("paper_conditions_ok", BOOL, "every condition of Thm 5.2.10 holds"),
            Field("blind_set_condition_ok", BOOL, "the blind-set condition holds"),
            Field("riccati_converges", BOOL, "the coupled Riccati recursion converges"),
            where="dkf expect",
        ),
        tolerance_fields(TOLERANCE_KEYS),
    )


def _pursuit() -> KindSchema:
    """seed 003 §IV–VI: trackers on S-T curves around a target, coupled by a network."""
    from theory.pursuit.case import (
        CONTROLLER_FIELDS,
        DEKF_FIELDS,
        EXPECT_KEYS,
        FIELDS,
        INITIAL_FIELDS,
        TARGET_FIELDS,
        TOLERANCE_KEYS,
        TRACKER_FIELDS_3D,
        VARIANTS,
        Controller,
    )

    zeros = "zeros"
    initial = block(
        INITIAL_FIELDS,
        Field(
            "position",
            VECTOR,
            "initial position, dim numbers",
            "m",
            "target start + (−40 + 5(i−1), −40 − 5(i−1), 0) for tracker i",
        ),
        Field("euler", VECTOR, "initial heading (2-D: 1 angle; 3-D: 3 Euler angles)", "rad", zeros),
        Field("gamma", NUMBER, "initial path parameter γ", "rad", "i − 1 for tracker i"),
        Field("gamma_dot", NUMBER, "initial γ̇ (controller II)", "rad/s", "ω_d(0)"),
        where="pursuit.trackers[].initial",
    )
    tracker = block(
        TRACKER_FIELDS_3D,
        Field(
            "r_x", POSITIVE, "semi-axis r_x of the S-T curve (eqs. (15)–(16))", "m", required=True
        ),
        Field("r_y", POSITIVE, "semi-axis r_y", "m", required=True),
        Field("r_z", POSITIVE, "semi-axis r_z (3-D only, required there)", "m", "—"),
        Field("c", NUMBER, "curve parameter c ∉ {0, 1} (3-D only, required there)", "", "—"),
        Field("gamma0", NUMBER, "phase γ₀ of the tracker on its curve", "rad", "0"),
        Field("initial", {}, "initial state of the simulation", default="below", fields=initial),
        where="pursuit.trackers[]",
    )
    target = block(
        TARGET_FIELDS,
        Field("offset", VECTOR, "target's constant offset", "m", zeros),
        Field("velocity", VECTOR, "target's constant velocity", "m/s", zeros),
        Field("amplitude", VECTOR, "amplitude of its sinusoidal motion", "m", zeros),
        Field("frequency", VECTOR, "angular frequency of its sinusoidal motion", "rad/s", zeros),
        Field("phase", VECTOR, "phase of its sinusoidal motion", "rad", zeros),
        where="pursuit.target",
    )
    dekf = block(
        DEKF_FIELDS,
        Field("Ts", POSITIVE, "sampling period", "s", required=True),
        Field("sigma", POSITIVE, "range-noise standard deviation (eq. (10))", "m", required=True),
        Field("V", POSITIVE, "inverse measurement-noise weight V^[i]", "", required=True),
        Field("Q", MATRIX, "2·dim × 2·dim positive-definite process-noise weight", required=True),
        Field(
            "weights",
            one_of({"const": "uniform"}, MATRIX),
            "N × N row-stochastic fusion weights π^[i,j] on the in-edges",
            default="uniform",
        ),
        Field(
            "edges",
            EDGES,
            "directed 1-based pairs [s, r] of the fusion graph, when it differs from the "
            "coordination graph (the authors' 2-D three-tracker script)",
            default="pursuit.edges",
        ),
        Field(
            "predict_every",
            POSITIVE,
            "prediction period dividing Ts (the authors' scripts: 0.1); Q is the process noise "
            "of one prediction",
            "s",
            "Ts (Algorithm 2 as printed)",
        ),
        Field("x0", MATRIX, "initial estimates, N × 2·dim", "m, m/s", "the true states"),
        Field(
            "P0",
            one_of(MATRIX, list_of(MATRIX)),
            "initial covariance, 2·dim × 2·dim, or one per tracker",
            default="the filter's",
        ),
        where="pursuit.dekf",
    )
    laws = choice([c.value for c in Controller])
    published = block(
        CONTROLLER_FIELDS,
        Field("law", laws, "path-following law: I (eq. (49)) or II (eq. (50))", required=True),
        Field(
            "variant",
            choice(list(VARIANTS)),
            "analysed: the law as seed 003 analyses it; published: as the authors' scripts run "
            "it (0.1 s steps, clamps, theory/pursuit/published.py)",
            default="analysed",
        ),
        Field(
            "inputs_min",
            VECTOR,
            "lower clamps of the inputs (v, r) (published only)",
            "m/s, rad/s",
            "none",
        ),
        Field(
            "inputs_max",
            VECTOR,
            "upper clamps of the inputs (v, r) (published only)",
            "m/s, rad/s",
            "none",
        ),
        Field("gamma_ddot", VECTOR, "[min, max] clamp of γ̈ (published only)", "rad/s²", "none"),
        where="pursuit.controller",
    )
    return KindSchema(
        "pursuit",
        "Trackers that follow S-T curves around a moving target, coordinated over a directed "
        "network; `trackcert iss` checks the ISS conditions of seed 003 Thm 1/2, `trackcert "
        "simulate` runs the loop with the distributed EKF (Algorithm 2).",
        "seed 003 §IV–VI, eqs. (15)–(19), (45)–(50)",
        block(
            FIELDS,
            Field("dim", {"enum": [2, 3]}, "space dimension", required=True),
            Field(
                "controller",
                one_of(laws, mapping_of(*published)),
                "path-following law: I (eq. (49)) or II (eq. (50)); or a mapping choosing the "
                "variant: {law, variant, inputs_min, inputs_max, gamma_ddot}",
                required=True,
            ),
            Field(
                "duration",
                POSITIVE,
                "simulated time",
                "s",
                "450",
            ),
            Field("omega_bar", POSITIVE, "ω̄ of eqs. (18), (46)", "rad/s", required=True),
            Field("epsilon", VECTOR, "ε of eq. (19), dim numbers", "m", required=True),
            Field(
                "K_p",
                one_of(VECTOR, MATRIX),
                "diagonal of K_p, or a dim × dim symmetric positive-definite matrix",
                "1/s",
                required=True,
            ),
            Field("k_gamma", POSITIVE, "k_γ of eq. (50b); required for controller II", "", "—"),
            Field(
                "k_c", POSITIVE, "coordination gain k_c of eq. (45); required when N > 1", "", "—"
            ),
            Field(
                "trackers",
                {"minItems": 1},
                "one entry per tracker: its S-T curve and initial state",
                required=True,
                fields=tracker,
                many=True,
            ),
            Field(
                "edges",
                WEIGHTED_EDGES,
                "directed 1-based pairs [s, r]: tracker s sends to tracker r; or triples "
                "[s, r, a] with the weight a_rs = a > 0 of L = D_in − A (default 1)",
                default="[] (no links)",
            ),
            Field(
                "target", {}, "the target's motion", default="at rest at the origin", fields=target
            ),
            Field(
                "dekf",
                {},
                "the distributed EKF of the simulation (Algorithm 2)",
                default="no simulation settings",
                fields=dekf,
            ),
            where="pursuit",
        ),
        block(
            EXPECT_KEYS,
            Field("iss", BOOL, "every ISS condition of Thm 1/2 holds"),
            Field("delta_full_rank", BOOL, "Δ has full row rank"),
            Field("strongly_connected", BOOL, "the network is strongly connected"),
            Field("simulation_bounded", BOOL, "simulated runs stay bounded (no runaway)"),
            Field("runaways", {"type": "integer", "minimum": 0}, "runs stopped as runaways"),
            Field(
                "final_localization_error",
                VECTOR,
                "band [low, high] holding every tracker's final position error, mean over the runs",
                "m",
            ),
            Field(
                "mean_pursuit_error",
                VECTOR,
                "band [low, high] holding every tracker's mean pursuit error, mean over the runs",
                "m",
            ),
            where="pursuit expect",
        ),
        tolerance_fields(TOLERANCE_KEYS),
    )


def _pf() -> KindSchema:
    """seed 002 §3.3: the distributed TDOA particle filter's scenario."""
    from theory.particle.case import (
        EXPECT_KEYS,
        FIELDS,
        LEARNING_FIELDS,
        PARAM_NAMES,
        TOLERANCE_KEYS,
        ExchangeWeights,
        Model,
        ReceivedHeading,
    )

    count = {"type": "integer", "minimum": 0}
    by_node = {"type": "object", "additionalProperties": BOOL}
    target = block(
        PARAM_NAMES,
        Field("mu", NUMBER, "mean turn μ of the wrapped Cauchy (eq. (3.1))", "rad", "0"),
        Field("gamma", NUMBER, "concentration γ, 0 ≤ γ < 1", "", "0.7"),
        Field("kappa", POSITIVE, "Weibull shape κ of the step (eq. (3.2))", "", "2"),
        Field("lambda", POSITIVE, "Weibull scale λ of the step", "m", "3"),
        where="pf.target",
    )
    learning = block(
        LEARNING_FIELDS,
        Field("min_samples", count, "steps observed before the model is refitted", "", "10"),
        Field("gamma_max", NUMBER, "largest γ a fit may return", "", "0.95"),
        Field("burn_in", count, "steps before the learned model is used", "", "5"),
        where="pf.learning",
    )
    return KindSchema(
        "pf",
        "A distributed TDOA particle-filter scenario of seed 002: stationary nodes, a target "
        "moving as a DCRW, particle filters that share particles; `trackcert pf` runs it.",
        "seed 002 §3.2–3.3, eqs. (3.1)–(3.13)",
        block(
            FIELDS,
            Field("nodes", MATRIX, "stationary node positions, N × 2", "m", required=True),
            Field("edges", EDGES, "undirected links, 1-based pairs", default="[] (no links)"),
            Field(
                "filters", list_of(NODE_ID), "nodes running a particle filter", default="every node"
            ),
            Field(
                "workspace",
                MATRIX,
                "[[x_min, x_max], [y_min, y_max]] of the initial particles and the target's start",
                "m",
                "[[-60, 60], [-60, 60]]",
            ),
            Field(
                "particles",
                {"type": "integer", "minimum": 2},
                "particles P per filter",
                default="100",
            ),
            Field(
                "share", count, "particles m shared per step (0: no consensus step)", default="10"
            ),
            Field("steps", {"type": "integer", "minimum": 1}, "target moves", default="100"),
            Field("runs", {"type": "integer", "minimum": 1}, "Monte Carlo runs", default="50"),
            Field("seed", count, "base seed (run r uses seeds [seed, r, ·])", default="0"),
            Field("noise_sigma", POSITIVE, "true TDOA noise standard deviation", "m", "1.0"),
            Field(
                "filter_sigma", POSITIVE, "σ the filter assumes in eq. (3.11)", "m", "noise_sigma"
            ),
            Field(
                "target",
                {},
                "the target's true DCRW",
                default="μ 0, γ 0.7, κ 2, λ 3",
                fields=target,
            ),
            Field(
                "model",
                choice([m.value for m in Model]),
                "the particles' propagation model",
                default=Model.DCRW.value,
            ),
            Field(
                "exchange_weights",
                choice([e.value for e in ExchangeWeights]),
                "the weight a received particle gets",
                default=ExchangeWeights.SENDER.value,
            ),
            Field(
                "exchange_rounds",
                {"type": "integer", "minimum": 1},
                "rounds of exchange per step",
                default="1",
            ),
            Field(
                "received_heading",
                choice([h.value for h in ReceivedHeading]),
                "the heading a received particle gets",
                default=ReceivedHeading.SENDER.value,
            ),
            Field(
                "uniform_max_step",
                POSITIVE,
                "the learner's uniform prior on step length",
                "m",
                "8.0",
            ),
            Field(
                "learning", {}, "the online learner's settings", default="below", fields=learning
            ),
            where="pf",
        ),
        block(
            EXPECT_KEYS,
            Field("converges", by_node, "node id → whether its filter converges (Figs. 3.2–3.3)"),
            Field(
                "consensus_helps",
                NODE_ID,
                "a node whose error the consensus step lowers (Fig. 3.4)",
            ),
            Field(
                "learned_beats_gaussian",
                NODE_ID,
                "a node where the learned model beats the Gaussian one (Fig. 3.5)",
            ),
            Field(
                "learned_pdfs_centre",
                NODE_ID,
                "a node where no learned parameter is biased (Fig. 3.6)",
            ),
            Field(
                "learned_biased",
                {"type": "object", "additionalProperties": list_of(choice(PARAM_NAMES))},
                "node id → its biased parameters",
            ),
            where="pf expect",
        ),
        tolerance_fields(TOLERANCE_KEYS),
    )


SCHEMAS: dict[str, Callable[[], KindSchema]] = {
    "tdoa": _tdoa,
    "tdoa-sim": _tdoa_sim,
    "dkf": _dkf,
    "pursuit": _pursuit,
    "pf": _pf,
}
"""Kind → its schema's builder (the same kinds as :data:`theory.kinds.KINDS`)."""


def kind_schema(kind: str) -> KindSchema:
    """The schema of case kind ``kind``; a :class:`CaseError` for an unknown kind."""
    if kind not in SCHEMAS:
        raise CaseError("KIND", f"one of {', '.join(SCHEMAS)}", kind, file=COMMAND_LINE)
    return SCHEMAS[kind]()
