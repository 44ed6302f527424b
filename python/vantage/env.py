"""A researcher's planner in Vantage's loop: ExploreEnv, an environment over the loop of
`vantage explore` (scan, register, segment, integrate) with the Gymnasium API, and bench_policy,
which runs a policy through `vantage bench`'s sweep so its rows land in the same scans.csv.

Neither needs the gymnasium package. The observation a policy sees (a dict):

- ``cells``: the map's cell states, uint8 of the grid's shape, indexed [i, j, k]
  (``vantage.UNOBSERVED`` = 0, ``vantage.FREE`` = 1, ``vantage.OCCUPIED`` = 2; cell (i, j, k)
  spans ``grid.origin + (i, j, k) * grid.resolution`` to the next corner [m]);
- ``pose``: the 4 x 4 sensor pose T_world_sensor of the last scan (x forward, y left, z up);
- ``candidates``: the candidate views' poses, n x 4 x 4;
- ``taken``: bool n, the candidates taken (the start's too, when it is one);
- ``travel``: float n, the travel from the last view to each candidate under the run's travel
  rule [m] (ring: the walk around the table; hemisphere: the straight line);
- ``scan``: the scans taken so far (1 after reset).
"""

import time as _time

import numpy as _np

from . import _vantage

__all__ = ["ActionSpace", "ExploreEnv", "bench_policy", "random_policy"]


class ActionSpace:
    """The candidates as a Gymnasium-style Discrete space: actions 0 .. n - 1."""

    def __init__(self, n, seed=None):
        """Actions 0 .. n - 1; `seed` seeds sample()'s generator (numpy's default_rng;
        None: fresh entropy)."""
        self.n = int(n)
        self._rng = _np.random.default_rng(seed)

    def seed(self, seed=None):
        """Reseeds sample()'s generator (numpy's default_rng) with `seed`; None: fresh
        entropy."""
        self._rng = _np.random.default_rng(seed)

    def sample(self, mask=None):
        """A random action, uniformly: any of 0 .. n - 1, or with `mask` (bool n, e.g.
        ~obs['taken']) one where the mask holds. ValueError when the mask allows none."""
        if mask is None:
            return int(self._rng.integers(self.n))
        choices = _np.flatnonzero(_np.asarray(mask, dtype=bool))
        if choices.size == 0:
            raise ValueError("sample: the mask allows no action")
        return int(self._rng.choice(choices))

    def contains(self, action):
        """Whether `action` is an integer (a Python or numpy one, not a bool) in
        0 .. n - 1."""
        try:
            a = _index(action)
        except TypeError:
            return False
        return 0 <= a < self.n

    def __repr__(self):
        return f"ActionSpace(n={self.n})"


def _index(action):
    """An action as an int: any integer (numpy's too), never a bool or a float."""
    if isinstance(action, (bool, _np.bool_)):
        raise TypeError("a bool")
    return int(action.__index__())


class ExploreEnv:
    """One table-top or object exploration as a Gymnasium environment: ``reset(seed) -> (obs,
    info)``, ``step(action) -> (obs, reward, terminated, truncated, info)``.

    scene: a ``Scene`` (``object_scene(...)`` too), a built-in scene's name, a scene file (table
    tops, generated piles, object files) or a mesh file or built-in model (a single object on its
    view sphere, docs/objects.md).
    candidates: a candidate set's name (``candidate_sets()``: ``'ring'``, ``'hemisphere'``,
    ``'sphere'``, ``'view-sphere'``); ``''``: the scene's own (a table top's ring, an object's
    view sphere).
    scans: the episode's scans, the start's included (``vantage explore --scans``).
    seed: the sweep seed of the first episode (``vantage bench --seed``); the run's noise seed is
    mixed from it, the scene's name and `start` as the bench mixes it, so an episode with seed s
    from start t meets the sensor and pose noise of trial t of ``vantage bench --seed s``.
    start: the index of the scene's start pose (the bench's trial t starts from t mod starts).
    reference: a built-in method's name (``'greedy'``, ``'probabilistic'``, ...) or None: with
    one, ``info['reference']`` holds that method's decision on each observation (its predicted
    gain of every candidate, NaN where taken, and its choice), and the run's settings are that
    method's (its a fit, if it has one); None: greedy's settings, and no predictions.
    coverage_tolerance: the yardstick's tolerance [cells], 0 or 1; -1: the scene's own (1 on a
    table top, 0 for an object, MA-SCVP's). An object's poses are exact, as ``explore --object``.
    num_threads: threads for scans, mapping and predictions (0: all cores; results do not
    depend on it).

    An action is a candidate's index; taken ones and any after the end are refused (ValueError,
    one line). reward is the scan's new surface coverage (surface_coverage's increase, the
    yardstick's: share of the visible object surface). terminated is True once every scan asked
    for is taken or no candidate is left; truncated is always False. info holds the scan's
    scans.csv columns (surface_coverage, raw_surface_coverage, coverage, unobserved,
    actual_gain [cells], travel_m [m], plan_seconds [s]: the decision's time, from the
    observation's return to step's call), and stop_reason at the end. The same seed gives the
    same episode for the same actions.

    obs: ``cells`` (each cell's class: UNOBSERVED, FREE, OCCUPIED) and ``log_odds`` (its
    occupancy log-odds, 0 unknown), both of the grid's shape [i, j, k]; ``pose``, the sensor's
    believed pose (4 x 4); ``candidates`` (K x 4 x 4); ``taken`` (K bools); ``travel`` to each
    candidate [m]; ``scan``, the scans so far.

    truth: the yardstick's truth of the scene and candidates, which no observation holds: for
    labels (what each view would add, as a learned planner's training needs) and for judging
    choices, never for a policy's decision. A dict of cell indices (linear, x fastest:
    ``numpy.unravel_index(c, obs["cells"].shape, order="F")`` is the cell's [i, j, k]):
    ``surface`` (the object surface cells S), ``visible`` (V, the cells of S some candidate or
    start hits noise-free), ``views`` and ``starts`` (per candidate and per start pose, the cells
    of V its noise-free scan covers at the tolerance), all ascending uint32 arrays, and the
    tolerance (``tolerance_cells``, ``tolerance_m``).
    """

    metadata = {"render_modes": []}

    def __init__(self, scene, candidates="", scans=10, seed=1, start=0, reference=None,
                 coverage_tolerance=-1, num_threads=0):
        """The environment of the class's docstring; computes the yardstick's truth for the
        candidate set once (seconds on a 129 x 129 x 65 grid). ValueError (one line) for an office
        scene, a start out of range, an unknown candidate set or method."""
        for name, value in (("scans", scans), ("start", start), ("seed", seed),
                            ("coverage_tolerance", coverage_tolerance),
                            ("num_threads", num_threads)):
            if isinstance(value, bool) or not isinstance(value, (int, _np.integer)):
                raise TypeError(f"{name} must be an integer, got {value!r}")
        if scans < 1:
            raise ValueError(f"scans must be >= 1, got {scans}")
        if seed < 0:
            raise ValueError(f"seed must be >= 0, got {seed}")
        self._run = _vantage._ExploreRun(scene, candidates, int(scans), int(start), reference,
                                         int(coverage_tolerance), int(num_threads))
        self._reference = reference
        self._seed = int(seed)
        self._episodes = 0
        self._coverage = 0.0
        self._handed = None  # when the last observation was returned
        self._truth = None  # the yardstick's truth as a dict, made on first use
        self.candidates = self._run.candidates
        self.action_space = ActionSpace(len(self.candidates), seed)
        self.scene = self._run.scene
        self.grid = self._run.grid
        self.fov = self._run.fov
        self.scans = self._run.scans

    @property
    def truth(self):
        """The yardstick's truth (the class's docstring), computed by the constructor."""
        if self._truth is None:
            self._truth = self._run.truth
        return self._truth

    @property
    def seed(self):
        """The sweep seed of the current episode."""
        return self._seed

    def reset(self, seed=None, options=None):
        """Starts an episode: the first scan, from the start pose. seed: the sweep seed (None:
        the constructor's for the first episode, one more than the last for each later one).
        Returns (obs, info)."""
        if seed is not None:
            if isinstance(seed, bool) or not isinstance(seed, (int, _np.integer)) or seed < 0:
                raise ValueError(f"seed must be an integer >= 0, got {seed!r}")
            self._seed = int(seed)
        elif self._episodes > 0:
            self._seed += 1
        self._episodes += 1
        self._run.reset(self._seed)
        info = self._run.info()
        self._coverage = info["surface_coverage"] or 0.0
        return self._observe(info)

    def step(self, action):
        """Takes the next scan from candidate `action`. Returns (obs, reward, terminated,
        truncated, info). ValueError (one line) for an action out of range, taken, or not an
        integer, and for a step after the end; RuntimeError before reset()."""
        if self._handed is None:
            raise RuntimeError("no episode yet: call reset() first")
        seconds = _time.perf_counter() - self._handed
        try:
            view = _index(action)
        except (TypeError, AttributeError):
            raise ValueError(f"action {action!r} is not a candidate's index (an integer)") from None
        if self._run.done:
            raise ValueError(f"the episode is over ({self._run.info()['stop_reason']}): "
                             "call reset()")
        self._run.step(view, seconds)
        info = self._run.info()
        coverage = info["surface_coverage"] or 0.0
        reward = coverage - self._coverage
        self._coverage = coverage
        obs, info = self._observe(info)
        return obs, reward, bool(self._run.done), False, info

    def _observe(self, info):
        obs = self._run.observation()
        if self._reference is not None and not self._run.done:
            info["reference"] = self._run.propose()
        self._handed = _time.perf_counter()
        return obs, info

    def close(self):
        """Nothing to release: the episode's map and scans are freed with the environment.
        There for the Gymnasium API."""

    def __repr__(self):
        return (f"ExploreEnv({self.scene.name!r}, candidates={len(self.candidates)}, "
                f"scans={self.scans}, seed={self._seed})")


def random_policy(seed=0):
    """A policy that takes an untaken candidate uniformly at random (numpy's generator, seeded
    once): a baseline for bench_policy."""
    rng = _np.random.default_rng(seed)

    def policy(obs):
        return int(rng.choice(_np.flatnonzero(~obs["taken"])))

    policy.__name__ = "random-policy"
    return policy


def bench_policy(policy, scenes, trials=10, out="results/bench-policy", name=None, scans=10,
                 candidates="", seed=1, coverage_tolerance=-1, generated=0, objects=None,
                 generated_seed=1, num_threads=0):
    """Runs `policy` (obs -> a candidate's index; obs as ExploreEnv's) through the sweep that
    ``vantage bench tabletop`` runs with the same options: the same scenes, starts (trial t
    from start t mod starts), seeds, loop and yardstick, one trial file each in out/trials/,
    then out/scans.csv with the bench's columns, the method column `name` (default: the
    policy's __name__). Into a folder of ``vantage bench`` with the same settings (sweep.json)
    its trials land beside the methods' (or join them with ``vantage bench merge``), and
    ``python3 scripts/plot_bench.py out`` compares it with them. Trials already in the folder
    are skipped, as the bench resumes.

    Returns the number of trials run now. A policy that raises (RuntimeError) or returns a
    non-integer, a candidate out of range or one already taken (ValueError) stops the sweep with
    one line naming the trial and scan; that trial leaves no file and scans.csv is not written
    (the trials finished before it are kept whole, to resume)."""
    if not callable(policy):
        raise TypeError(f"policy must be callable (obs -> index), got {policy!r}")
    if name is None:
        name = getattr(policy, "__name__", "policy")
    if isinstance(scenes, str):
        scenes = [scenes]
    if objects is None:
        objects = -1  # the generator's default
    return _vantage._bench_policy(policy, str(name), list(scenes), int(trials), str(out),
                                  int(scans), candidates, int(seed), int(coverage_tolerance),
                                  int(num_threads), int(generated), int(objects),
                                  int(generated_seed))
