"""Every registered exercise: the reference passes, a stub is 'not attempted', mistakes are diagnosed."""

import builtins
import dis
import sys
import types

import numpy as np
import pytest

from camlab import exercises
from camlab.exercises import all_exercises, check, solution, solution_source, worst_mismatch

EXERCISES = all_exercises()


def _stub(*args):
    raise NotImplementedError


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_reference_passes(name, capsys):
    assert check(name, EXERCISES[name].reference).passed is True
    assert "correct on all" in capsys.readouterr().out


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_stub_reports_not_attempted(name, capsys):
    assert check(name, _stub).passed is False
    assert "not attempted yet" in capsys.readouterr().out


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_wrong_variants_are_diagnosed(name):
    variants = EXERCISES[name].wrong_variants
    assert variants, f"{name}: register at least one plausible wrong answer"
    for wrong, phrase in variants:
        with pytest.raises(AssertionError) as info:
            check(name, wrong)
        message = str(info.value)
        assert "likely cause" in message or "raised" in message, message
        assert phrase in message, f"{name}: diagnosis lacks {phrase!r}:\n{message}"


# Lessons whose every exercise must have a teaching solution (extend as lessons gain theirs).
TEACHING_LESSONS = {"00", "01", "02", "03", "04", "05", "06", "07", "08", "10", "11", "12"}
TEACHING = sorted(n for n, e in EXERCISES.items() if e.teaching is not None)


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_solution_prints_the_teaching_solution_or_the_library_source(name, capsys):
    exercise = EXERCISES[name]
    assert (
        solution(name) is None
    )  # a bare call ending a cell shows the code once, not again as Out[]
    source = solution_source(name)
    shown = exercise.teaching or exercise.reference
    assert f"def {shown.__name__}(" in source
    assert capsys.readouterr().out == source + "\n"


@pytest.mark.parametrize(
    "name", sorted(n for n, e in EXERCISES.items() if e.lesson in TEACHING_LESSONS)
)
def test_exercise_has_a_teaching_solution_named_like_it(name):
    teaching = EXERCISES[name].teaching
    assert teaching is not None, (
        f"{name}: register a teaching solution (Exercise(..., teaching=fn))"
    )
    assert teaching.__name__ == name, (
        f"{name}: name the teaching solution like the student's function"
    )


@pytest.mark.parametrize("name", TEACHING)
def test_teaching_solution_agrees_with_the_library(name, capsys):
    assert check(name, EXERCISES[name].teaching).passed is True
    assert "correct on all" in capsys.readouterr().out


def _globals_used(code: types.CodeType) -> set[str]:
    names = {
        i.argval for i in dis.get_instructions(code) if i.opname in ("LOAD_GLOBAL", "LOAD_NAME")
    }
    for const in code.co_consts:
        if isinstance(const, types.CodeType):
            names |= _globals_used(const)
    return names


@pytest.mark.parametrize("name", TEACHING)
def test_teaching_solution_is_self_contained_numpy(name):
    teaching = EXERCISES[name].teaching
    for used in _globals_used(teaching.__code__):
        if hasattr(builtins, used):
            continue
        assert teaching.__globals__.get(used) is np, (
            f"{name}: the teaching solution uses {used!r}; it may use only numpy (np) and builtins"
        )


@pytest.mark.parametrize("name", TEACHING)
def test_printed_solution_runs_on_its_own(name, capsys):
    """What solution() prints, pasted into a fresh namespace with only numpy, defines a function that passes.

    The globals check above cannot see a default argument naming a module constant
    (``steps=NEWTON_STEPS`` raised NameError once pasted into a lesson).
    """
    source = solution_source(name).split("\n# camlab's own")[0]
    namespace = {"np": np}
    exec(compile(source, f"<solution {name}>", "exec"), namespace)
    assert check(name, namespace[name]).passed is True


def test_teaching_solution_check_catches_a_call_into_camlab():
    def leaky(x):
        return camlab_helper(x)  # noqa: F821

    assert "camlab_helper" in _globals_used(leaky.__code__)


def test_large_array_mismatch_is_summarised_not_printed():
    from camlab.exercises._answers import worst_mismatch
    from camlab.exercises._core import _fmt

    expected = np.zeros((40, 50, 3))
    got = expected.copy()
    got[7, 9, 2] = 5.0
    assert _fmt(got).startswith("<array of shape (40, 50, 3)")
    line = worst_mismatch(got, expected)
    assert (
        "(row, column, channel) (7, 9, 2): got 5, expected 0 (1 of 6000 entries differ by more than rtol 1e-05, atol 1e-08)"
        in line
    )


def test_forgotten_return_is_named():
    with pytest.raises(AssertionError, match="forget `return`"):
        check("lift", lambda p: None)


def test_none_where_the_answer_is_nan_is_told_to_return_nan():
    """A student who returns None for "no focal fits" is told to return NaN, not to add a `return`."""
    reference = EXERCISES["focal_from_rotation_homography"].reference

    def none_for_undefined(H, shape):
        f = reference(H, shape)
        return None if np.isnan(np.asarray(f, float)).any() else f

    with pytest.raises(AssertionError, match=r"answer here is \[nan, nan\].*not None") as info:
        check("focal_from_rotation_homography", none_for_undefined)
    assert "forget" not in str(info.value)


def test_check_functions_exist_by_name():
    for name in EXERCISES:
        assert callable(getattr(exercises, f"check_{name}"))
    with pytest.raises(AttributeError):
        exercises.check_no_such_exercise  # noqa: B018
    with pytest.raises(KeyError, match="no exercise 'nope'"):
        solution("nope")


def test_student_crash_is_reported_with_its_input():
    with pytest.raises(AssertionError, match=r"raised ZeroDivisionError.*\n  on input"):
        check("intersect_lines", lambda l1, l2: 1 / 0)


def test_a_broadcasting_error_gets_a_hint_naming_keepdims():
    def project(X, f):
        return (
            f * np.ones((6, 2)) / np.ones(6)
        )  # numpy's own error for (6, 2) / (6,), as X[:, :2] / X[:, 2] gives

    with pytest.raises(
        AssertionError,
        match=r"raised ValueError.*\n.*\n  likely cause: a broadcasting slip.*X\[:, 2:3\]",
    ):
        check("pinhole_projection", project)


@pytest.mark.parametrize("divide", [lambda x: (x / x[:, 2])[:, :2], lambda x: x[:, :2] / x[:, 2]])
def test_project_points_divided_without_keepdims_gets_the_hint(divide):
    # lesson 04's exercise: the (N, 3) or (N, 2) block divided by the (N,) column x[:, 2]
    def project_points(P, X):
        return divide(np.c_[X, np.ones(len(X))] @ np.asarray(P).T)

    with pytest.raises(AssertionError, match=r"likely cause: a broadcasting slip.*keepdims=True"):
        check("project_points", project_points)


def test_pinhole_checks_pass_right_answers_in_other_forms(capsys):
    assert check(
        "pinhole_projection", lambda X, f: f * np.asarray(X)[:, :2] / np.asarray(X)[:, [2]]
    )
    assert check(
        "pinhole_projection", lambda X, f: (f * np.asarray(X).T[:2] / np.asarray(X).T[2]).T
    )
    assert check("best_pinhole_diameter", lambda f, lam: (2.44 * lam * f) ** 0.5)


def test_best_pinhole_accepts_a_numerical_minimiser_and_rejects_a_few_percent_off(capsys):
    from scipy.optimize import minimize_scalar

    def bounded(f, lam):  # stops about 0.4 % from d*, where the blur is within 1e-5 of its least
        return minimize_scalar(
            lambda d: d + 2.44 * lam * f / d, bounds=(1e-6, 1e-2), method="bounded"
        ).x

    assert check("best_pinhole_diameter", bounded)
    with pytest.raises(AssertionError, match="minimise the total blur"):
        check("best_pinhole_diameter", lambda f, lam: 1.05 * (2.44 * lam * f) ** 0.5)


def test_a_function_that_changes_its_input_in_place_fails_naming_the_argument(capsys):
    def project_in_place(X, f):
        X[:, :2] *= f / X[:, 2:3]
        return X[:, :2]

    with pytest.raises(
        AssertionError, match=r"changed its input `X` in place(.|\n)*work on a copy"
    ):
        check("pinhole_projection", project_in_place)


def test_counting_columns_from_one_is_named_as_such():
    for one_based in (
        lambda X, f: f * X[:, 1:3] / X[:, 3:4],
        lambda X, f: f * X[:, [1, 2]] / X[:, [3]],
    ):
        with pytest.raises(AssertionError, match="counting columns from 1"):
            check("pinhole_projection", one_based)


def test_a_wrong_number_prints_as_a_plain_float():
    with pytest.raises(AssertionError) as info:
        check("best_pinhole_diameter", lambda f, lam: np.float64(1.0))
    assert "np.float64" not in str(info.value) and "got      1.0" in str(info.value)


def test_solution_ending_a_cell_shows_no_second_copy():
    """Through IPython's own display path: the printed code once, and no Out[] after it."""
    from IPython.core.interactiveshell import InteractiveShell
    from IPython.utils.capture import capture_output

    shell = InteractiveShell.instance()
    try:
        with capture_output() as shown:
            result = shell.run_cell(
                'from camlab.exercises import solution\nsolution("pinhole_projection")'
            )
    finally:
        InteractiveShell.clear_instance()
    assert result.success and result.result is None
    assert shown.stdout.count("def pinhole_projection(") == 1 and "Out[" not in shown.stdout


def test_estimate_affine_camera_accepts_a_column_of_ones_instead_of_centring(capsys):
    from camlab.exercises.affine_cameras._estimation_variants import _estimate_with_ones

    assert check("estimate_affine_camera", _estimate_with_ones).passed is True


def test_estimate_affine_camera_accepts_hz_normalisation_undone_in_the_right_order(capsys):
    """H&Z algorithm 7.2: normalise both point sets, fit, then P = inv(T_uv) @ P_n @ T_X (the check's
    diagnosis names the wrong order, T_uv @ P_n @ inv(T_X), as such)."""
    from camlab.exercises.affine_cameras._estimation_variants import estimate_normalised

    assert check("estimate_affine_camera", estimate_normalised("right")).passed is True


@pytest.mark.parametrize(
    "solve",
    [
        lambda A, uv: np.linalg.pinv(A) @ uv,  # the pseudo-inverse
        lambda A, uv: np.linalg.solve(A.T @ A, A.T @ uv),  # the normal equations
    ],
)
def test_estimate_affine_camera_accepts_other_least_squares_solvers(solve, capsys):
    def student(X, uv):
        A = np.c_[X, np.ones(len(X))]
        return np.vstack([solve(A, uv).T, [0.0, 0.0, 0.0, 1.0]])

    assert check("estimate_affine_camera", student).passed is True


def test_paraperspective_accepts_the_first_order_taylor_expansion_by_central_differences(capsys):
    """Para-perspective is perspective linearised at X0: a camera built from the numerical Jacobian
    of the projection at X0 is a right answer in another form."""

    def student(camera, X0):
        J = np.column_stack(
            [(camera.project(X0 + e) - camera.project(X0 - e)) / 2e-4 for e in 1e-4 * np.eye(3)]
        )
        x0 = camera.project(X0)
        return np.vstack([np.c_[J, x0 - J @ X0], [0.0, 0.0, 0.0, 1.0]])

    assert check("paraperspective_approximation", student).passed is True


def _in_float32(value):
    """A right answer as a student computing in float32 would return it."""
    if isinstance(value, tuple) and hasattr(value, "_fields"):
        return type(value)(*(_in_float32(v) for v in value))
    if isinstance(value, (tuple, list)):
        return type(value)(_in_float32(v) for v in value)
    if np.asarray(value).dtype.kind == "f":
        return np.float32(value) if np.ndim(value) == 0 else np.asarray(value, dtype=np.float32)
    return value


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_right_answer_in_float32_passes(name, capsys):
    reference = EXERCISES[name].reference
    assert check(name, lambda *args: _in_float32(reference(*args))).passed is True
    assert "correct on all" in capsys.readouterr().out


def _in_float16(value):
    """A right answer cast to float16, as in round 5's review of lesson 03 (it passed a half-pixel slip)."""
    if isinstance(value, tuple) and hasattr(value, "_fields"):
        return type(value)(*(_in_float16(v) for v in value))
    if isinstance(value, (tuple, list)):
        return type(value)(_in_float16(v) for v in value)
    if np.asarray(value).dtype.kind == "f":
        with np.errstate(over="ignore"):  # entries beyond float16's 65504 become inf: still float16
            return np.float16(value) if np.ndim(value) == 0 else np.asarray(value, dtype=np.float16)
    return value


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_float16_answer_is_rejected_naming_its_precision(name, capsys):
    """float16 cannot tell 2015.5 from 2016: no tolerance fits it, so its type is named instead."""
    from camlab.exercises._answers import _holds_floats

    exercise = EXERCISES[name]
    if not _holds_floats(exercise.reference(*exercise.cases()[0])):
        pytest.skip("the answer holds no floats")
    with pytest.raises(AssertionError, match="your answer is float16"):
        check(name, lambda *args: _in_float16(exercise.reference(*args)))


def test_float16_slips_of_lesson_03_are_rejected():
    """Round 5 (D2): these passed as float16 through a tolerance widened to 100 float16 epsilons."""
    from camlab.exercises.digital_sensor.datasheet import _datasheet_variant
    from camlab.exercises.digital_sensor.demosaic import _reflect_border_demosaic

    slips = {
        "intrinsics_from_datasheet": (
            lambda f, s, n: _datasheet_variant(f, s, n, cx=n[0] / 2, cy=n[1] / 2),
            lambda f, s, n: _datasheet_variant(f, s, n, fy=f * n[0] / s[0]),
        ),
        "demosaic_bilinear": (_reflect_border_demosaic,),
    }
    for name, wrongs in slips.items():
        for wrong in wrongs:
            with pytest.raises(AssertionError, match="float16"):
                check(name, lambda *args, wrong=wrong: np.asarray(wrong(*args), dtype=np.float16))


def test_float32_answer_is_held_to_float32_precision_not_beyond():
    from camlab.exercises._answers import Tolerance

    tol = Tolerance(rtol=1e-9, atol=0.0)
    expected = np.array([1.2, 2.4, 6.0])
    assert tol.for_answer(expected, expected) == tol  # float64: the exercise's own
    widened = tol.for_answer(expected.astype(np.float32), expected)
    assert widened.rtol == pytest.approx(
        100 * np.finfo(np.float32).eps
    ) and widened.atol == pytest.approx(6 * widened.rtol)
    with pytest.raises(
        AssertionError, match="wrong answer"
    ):  # a real mistake in float32 still fails
        check(
            "disparity_to_depth",
            lambda d, f, B, o: np.float32(1.001) * (f * B / (d + o)).astype(np.float32),
        )


def test_mismatch_line_counts_with_the_exercises_tolerance_and_shows_the_digits():
    from camlab.exercises._answers import Tolerance

    got, expected = np.array([1.2, 2.4 + 1e-12, 6.0]), np.array([1.2, 2.4, 6.0])
    line = worst_mismatch(got, expected, Tolerance(rtol=1e-14, atol=0.0))
    assert (
        "got 2.400000000001, expected 2.4 (1 of 3 entries differ by more than rtol 1e-14, atol 0)"
        in line
    )


def test_check_result_is_falsy_for_a_stub_and_prints_nothing_in_ipython(capsys):
    from IPython.core.interactiveshell import InteractiveShell

    result = check("lift", _stub)
    assert not result and repr(result) == "CheckResult('lift', passed=False)"
    assert check("lift", EXERCISES["lift"].reference)
    shell = InteractiveShell.instance()
    try:
        assert shell.display_formatter.format(result) == ({}, {})  # ends a cell: no stray `False`
    finally:
        InteractiveShell.clear_instance()


@pytest.fixture
def short_time_limit(monkeypatch):
    from camlab.exercises import _core, _timer

    if not _timer.time_limit_applies():
        pytest.skip("the time limit needs SIGALRM in the main thread")
    monkeypatch.setattr(_core, "TIME_LIMIT_S", 0.3)


def _never_returns(*args):
    """Spins (for 10 s, so that a check without a time limit fails instead of hanging the suite)."""
    import time

    end = time.monotonic() + 10
    while time.monotonic() < end:
        try:
            pass
        except Exception:  # a student's catch-all must not swallow the time limit
            pass


def test_a_function_that_never_returns_is_stopped_naming_its_input(short_time_limit):
    import time

    start = time.monotonic()
    with pytest.raises(
        AssertionError,
        match=r"(?s)still running after 0.3 s on test input 1 of \d+.*input    \(\[\[",
    ):
        check("apply_homography", _never_returns)
    assert time.monotonic() - start < 5


def test_time_limit_on_a_later_input_names_that_input(short_time_limit):
    calls = []

    def slow_on_the_second(*args):
        calls.append(1)
        if len(calls) == 2:
            _never_returns()
        return EXERCISES["intersect_lines"].reference(*args)

    with pytest.raises(AssertionError, match="on test input 2 of"):
        check("intersect_lines", slow_on_the_second)


def test_check_takes_a_shorter_time_limit_as_lesson_00_shows_it():
    """Lesson 00 runs a never-ending lift under check_lift(..., time_limit_s=1) where the limit applies."""
    import time

    from camlab.exercises import TIME_LIMIT_S, time_limit_applies

    if not time_limit_applies():
        pytest.skip("the time limit needs SIGALRM in the main thread")
    start = time.monotonic()
    with pytest.raises(
        AssertionError,
        match=r"still running after 0.4 s on test input 1 of 5, so the check stopped it",
    ):
        exercises.check_lift(_never_returns, time_limit_s=0.4)
    assert time.monotonic() - start < 3 and TIME_LIMIT_S == 30


@pytest.mark.parametrize("bad", [0, -1.0, float("nan")])
def test_a_time_limit_that_is_not_a_positive_number_is_a_clear_error(bad):
    from camlab import CamlabInputError

    with pytest.raises(
        CamlabInputError, match=r"check: time_limit_s: expected a positive number of seconds, got"
    ):
        check("lift", EXERCISES["lift"].reference, time_limit_s=bad)


def test_time_limit_applies_only_where_sigalrm_can_interrupt_the_main_thread():
    import signal
    import threading

    from camlab.exercises import time_limit_applies

    assert time_limit_applies() == (
        hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()
    )
    seen = []
    worker = threading.Thread(target=lambda: seen.append(time_limit_applies()))
    worker.start()
    worker.join()
    assert seen == [False]


def test_time_limit_restores_an_outer_timer():
    import signal

    from camlab.exercises._timer import time_limit

    fired = []
    previous = signal.signal(signal.SIGALRM, lambda *a: fired.append(1))
    try:
        signal.setitimer(signal.ITIMER_REAL, 30.0)
        with time_limit(5.0):
            pass
        remaining, _ = signal.getitimer(signal.ITIMER_REAL)
        assert 25 < remaining <= 30 and signal.getsignal(signal.SIGALRM) is not None and not fired
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


def test_time_limit_runs_without_a_timer_off_the_main_thread():
    import threading

    from camlab.exercises._timer import time_limit

    seen = []

    def worker():
        with time_limit(0.01):
            seen.append(sum(range(10)))

    thread = threading.Thread(target=worker)
    thread.start()
    thread.join(5)
    assert seen == [45]


@pytest.mark.parametrize("name", sorted(EXERCISES))
@pytest.mark.parametrize(
    "answer", ["oops", [np.zeros(2), 1.0], {"x": 1}], ids=["str", "ragged list", "dict"]
)
def test_an_answer_that_is_not_numbers_is_named_not_a_crash_inside_camlab(name, answer):
    with pytest.raises(AssertionError) as info:
        check(name, lambda *args: answer)
    message = str(info.value)
    assert "likely cause" in message, message
    expected = EXERCISES[name].reference(*EXERCISES[name].cases()[0])
    if isinstance(
        expected, (np.ndarray, float)
    ):  # answers of other kinds (pairs of arrays) have their own hints
        assert f"you returned a {type(answer).__name__}" in message, message


def test_lift_rejects_a_list_since_its_prompt_asks_for_an_array_and_names_the_fix():
    with pytest.raises(
        AssertionError,
        match=r"wrong type of answer.*\n.*\n  got      \[2\.5, 4\.25, 1\.0\]  \(a list\)"
        r"(.|\n)*you returned a list; return a numpy array of shape \(3,\)",
    ):
        check("lift", lambda p: [p[0], p[1], 1.0])


def test_ndarray_answer_is_not_demanded_where_the_prompt_does_not_ask(capsys):
    assert check(
        "pinhole_projection",
        lambda X, f: (f * np.asarray(X)[:, :2] / np.asarray(X)[:, [2]]).tolist(),
    )


def test_a_ragged_np_array_inside_the_students_function_gets_a_hint():
    with pytest.raises(
        AssertionError,
        match=r"raised ValueError(.|\n)*likely cause: an array beside numbers.*np\.append",
    ):
        check("lift", lambda p: np.array([p, 1]))


@pytest.mark.parametrize(
    "right",
    [
        lambda p: np.r_[p, 1],
        lambda p: np.hstack([p, 1]),
        lambda p: np.concatenate((p, [1.0])),
        lambda p: np.array([p[0], p[1], 1]),
        lambda p: np.append(p, 1).astype(np.float32),
    ],
    ids=["r_", "hstack", "concatenate", "int literal", "float32"],
)
def test_lift_passes_right_answers_in_other_forms(right, capsys):
    assert check("lift", right).passed is True


def test_a_right_answer_that_changes_its_input_in_place_fails_naming_the_argument():
    """An in-place change of the caller's array (a typical mistake) fails, even when the answer is right."""
    from camlab import distortion

    def scaled_in_place(uv, K, dist):
        out = distortion.distort_pixels(uv, K, dist)
        uv *= 1.0 + 0 * uv  # a no-op in value: nothing changes, so this passes
        return out

    def overwritten(uv, K, dist):
        uv[:] = distortion.distort_pixels(uv, K, dist)
        return uv

    assert check("distort_pixels", scaled_in_place)
    with pytest.raises(
        AssertionError,
        match=r"changed its input `uv` in place.*\n.*likely cause: an in-place operation",
    ):
        check("distort_pixels", overwritten)


def _dlt_rms_normalised(X, uv):
    """The normalised DLT with H&Z's RMS distances (camlab uses mean distances), at another scale."""
    from camlab.exercises.projective_camera._dlt_forms import dlt_unnormalised

    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)

    def normaliser(p):
        c = p.mean(axis=0)
        s = np.sqrt(p.shape[1] / np.mean(np.sum((p - c) ** 2, axis=1)))
        return np.block(
            [[s * np.eye(p.shape[1]), -s * c[:, None]], [np.zeros((1, p.shape[1])), 1.0]]
        )

    U, T = normaliser(X), normaliser(uv)
    P_hat = dlt_unnormalised(
        (np.c_[X, np.ones(len(X))] @ U.T)[:, :3], (np.c_[uv, np.ones(len(uv))] @ T.T)[:, :2]
    )
    return -42.0 * np.linalg.inv(T) @ P_hat @ U


def test_estimate_projection_matrix_accepts_rms_normalisation_at_another_scale(capsys):
    assert check("estimate_projection_matrix", _dlt_rms_normalised).passed is True


@pytest.mark.skipif(
    not hasattr(__import__("camlab.exercises._core").exercises._core, "_inputs_changed"),
    reason="the shared in-place detector (_core._inputs_changed) arrives from another branch",
)
def test_in_place_division_of_P_in_project_points_gets_a_hint():
    def project_points(P, X):
        P /= P[2, 3]  # changes the caller's camera.P
        x = np.c_[X, np.ones(len(X))] @ P.T
        return x[:, :2] / x[:, 2:]

    with pytest.raises(AssertionError, match=r"in place"):
        check("project_points", project_points)


@pytest.mark.parametrize("name", sorted(EXERCISES))
@pytest.mark.parametrize(
    "cast, phrase",
    [
        (lambda a: np.asarray(a).astype(str), "of text (dtype <U"),
        (lambda a: np.asarray(a) + 0j, "of complex numbers (dtype complex128)"),
        (lambda a: np.asarray(a).astype(object), "of Python objects"),
    ],
    ids=["text", "complex", "object"],
)
def test_the_right_numbers_as_text_complex_or_objects_are_rejected_naming_the_cause(
    name, cast, phrase
):
    """np.asarray(answer, dtype=float) reads '2.5' and drops an imaginary part: such answers must not pass."""
    exercise = EXERCISES[name]
    if not isinstance(exercise.reference(*exercise.cases()[0]), np.ndarray):
        pytest.skip("answers of other kinds (pairs of arrays) have their own checks")
    with pytest.raises(
        AssertionError, match=r"wrong type of answer(.|\n)*likely cause: you returned an ndarray "
    ) as info:
        check(name, lambda *args: cast(exercise.reference(*args)))
    assert phrase in str(info.value)


@pytest.mark.parametrize(
    "answer", ["2.5", np.complex128(2.5), [2.5, 4.25, "1"]], ids=["str", "complex", "mixed list"]
)
def test_a_number_as_text_or_complex_is_not_a_number(answer):
    from camlab.exercises import type_problem

    assert type_problem(answer, 2.5) or type_problem(answer, np.zeros(3))
    assert "complex number" in (type_problem(np.complex128(2.5), 2.5) or "")


def _grow(p):
    p = p.copy()
    p[2] = 1.0  # MATLAB grows an array this way; numpy cannot
    return p


def _read_from_1(p):
    return np.array([p[1], p[2], 1.0])


@pytest.mark.parametrize(
    "wrong, causes, not_said",
    [
        (_grow, ["cannot grow an array: a numpy array has a fixed size"], "counting"),
        (
            _read_from_1,
            [
                "counting from 1: numpy counts from 0, so the point's coordinates are p[0] (x) and p[1] (y)"
            ],
            "grow",
        ),
        (lambda p: np.vstack([p, 1.0]), ["np.vstack stacks its arguments as rows"], "np.c_"),
        (
            lambda p: np.zeros(3),
            ["x and y are 0: the array was created", "w = 0 makes an ideal point"],
            None,
        ),
        (
            lambda p: np.r_[p[::-1], 0.0],
            ["x and y are swapped", "w = 0 makes an ideal point"],
            None,
        ),
        (lambda p: np.r_[-p[0], p[1], 1.0], ["x changed sign"], "a unit change"),
        (lambda p: np.r_[p[0], 479.5 - p[1], 1.0], ["flipped it to a y-up convention"], "sign"),
        (
            lambda p: np.r_[p - [319.5, 239.5], 1.0],
            ["subtracted the image centre (319.5, 239.5)"],
            "mean",
        ),
        (
            lambda p: np.r_[p / [640, 480], 1.0],
            ["divided by the image size (640, 480)"],
            "stray factor",
        ),
        (lambda p: np.r_[p / 1000, 1.0], ["millimetre-metre conversion"], "stray factor"),
    ],
    ids=[
        "p[2] = 1",
        "1-based",
        "vstack",
        "zeros",
        "swapped and w = 0",
        "x sign",
        "y up",
        "centred",
        "over size",
        "mm",
    ],
)
def test_lift_hints_name_the_real_cause_not_the_batch_exercises(wrong, causes, not_said):
    """Index and joining slips on one (2,) point get hints about that point, not an (N, 3) array's columns;
    an answer wrong in x and y and in w is told both."""
    with pytest.raises(AssertionError) as info:
        check("lift", wrong)
    message = str(info.value)
    hint = message.split("likely cause")[-1]
    assert all(cause in hint for cause in causes), message
    assert "(N, 3)" not in message and "counting columns" not in message, message
    assert not not_said or not_said not in hint, message


@pytest.mark.parametrize(
    "batch_code, phrase",
    [
        (
            lambda p: np.hstack([p, np.ones((len(p), 1))]),
            r"batch code on one point(.|\n)*np\.append\(p, 1\.0\)",
        ),
        (
            lambda p: np.c_[p[:, 0], p[:, 1], np.ones(len(p))],
            r"no second axis(.|\n)*p\[0\] and p\[1\]",
        ),
        (
            lambda p: np.column_stack([p, np.ones(len(p))]),
            r"got shape \(2, 2\): np\.column_stack / np\.c_",
        ),
    ],
    ids=["hstack", "p[:, 0]", "column_stack"],
)
def test_lift_names_the_worked_examples_batch_code_copied_for_one_point(batch_code, phrase):
    with pytest.raises(AssertionError, match=phrase) as info:
        check("lift", batch_code)
    assert "1-based" not in str(info.value) and "counting columns from 1" not in str(info.value)


def _dlt_variant(X, uv, rows=2, normaliser="isotropic"):
    """A normalised DLT in another valid form: all three rows of u x P X, or per-axis normalisation."""
    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)

    def similarity(p):
        c = p.mean(axis=0)
        s = (
            1.0 / p.std(axis=0)
            if normaliser == "per-axis"
            else np.full(p.shape[1], np.sqrt(p.shape[1]) / np.mean(np.linalg.norm(p - c, axis=1)))
        )
        T = np.diag(np.append(s, 1.0))
        T[:-1, -1] = -s * c
        return T

    U, T = similarity(X), similarity(uv)
    Xn = np.c_[X, np.ones(len(X))] @ U.T
    un = np.c_[uv, np.ones(len(uv))] @ T.T
    blocks = []
    for Xh, (u, v, w) in zip(Xn, un, strict=True):
        z = np.zeros(4)
        rows_i = [np.r_[w * Xh, z, -u * Xh], np.r_[z, w * Xh, -v * Xh], np.r_[-v * Xh, u * Xh, z]]
        blocks += rows_i[:rows]
    P_hat = np.linalg.svd(np.array(blocks))[2][-1].reshape(3, 4)
    return np.linalg.inv(T) @ P_hat @ U


@pytest.mark.parametrize(
    "right",
    [
        lambda X, uv: _dlt_variant(X, uv, rows=3),
        lambda X, uv: _dlt_variant(X, uv, normaliser="per-axis"),
        lambda X, uv: __import__("camlab").camera.estimate_projection_matrix(X, uv, refine=True),
    ],
    ids=["three rows of the cross product", "per-axis normalisation", "refined by LM"],
)
def test_estimate_projection_matrix_passes_other_valid_normalised_answers(right, capsys):
    """Round 2 of lesson 04's review: these were rejected at 1.19 px and 0.06 px from camlab's estimate."""
    assert check("estimate_projection_matrix", right).passed is True


def test_estimate_projection_matrix_names_which_half_was_not_normalised():
    from camlab.exercises.projective_camera._dlt_forms import dlt_half

    with pytest.raises(
        AssertionError,
        match=r"(?s)different camera.*likely cause: the world points are not normalised",
    ):
        check("estimate_projection_matrix", lambda X, uv: dlt_half(X, uv, world=False))
    with pytest.raises(
        AssertionError, match=r"(?s)different camera.*likely cause: the pixels are not normalised"
    ):
        check("estimate_projection_matrix", lambda X, uv: dlt_half(X, uv, pixels=False))


@pytest.mark.parametrize(
    "world, pixels, cause",
    [
        ((True, False), (True, False), "the world points are centred but not scaled"),
        ((True, True), (True, False), "the pixels are centred but not scaled"),
        ((False, True), (False, True), "the world points are scaled but not centred"),
        ((True, True), (False, True), "the pixels are scaled but not centred"),
    ],
    ids=[
        "centred not scaled",
        "pixels centred not scaled",
        "scaled not centred",
        "pixels scaled not centred",
    ],
)
def test_estimate_projection_matrix_names_the_missing_part_of_a_normalisation(world, pixels, cause):
    """Final review of lesson 04: half normalisations were blamed on the wrong side or called 'no normalisation'."""
    from camlab.exercises.projective_camera._dlt_forms import dlt_partial

    with pytest.raises(AssertionError, match=r"(?s)likely cause: .*" + cause) as info:
        check(
            "estimate_projection_matrix",
            lambda X, uv: dlt_partial(X, uv, world=world, pixels=pixels),
        )
    assert "no normalisation" not in str(info.value) and "you normalised only" not in str(
        info.value
    )


def test_estimate_projection_matrix_names_the_classic_p34_dlt():
    """p34 = 1 by least squares without normalising is pixel-invariant: it was reported as 'pixels normalised'."""
    from camlab.exercises.projective_camera._dlt_forms import dlt_p34

    with pytest.raises(AssertionError, match=r"(?s)likely cause: you fixed p34 = 1"):
        check("estimate_projection_matrix", dlt_p34)


def test_rq_decomposition_has_a_negative_determinant_case_with_a_reflection():
    from camlab.exercises.projective_camera.rq import _rq_cases

    M = [m for (m,) in _rq_cases() if np.linalg.det(m) < 0]
    assert M, "no det M < 0 input: flipping M inside rq_decomposition would pass"
    K, R = __import__("camlab").camera.rq_decomposition(M[0])
    assert np.linalg.det(R) < 0 and np.all(np.diag(K) > 0)


# lesson 01's exercises: right answers in other valid forms pass, the typical slips get their own causes


def _K(f, pitch, size):
    return np.array(
        [[f / pitch, 0, (size[0] - 1) / 2], [0, f / pitch, (size[1] - 1) / 2], [0, 0, 1]]
    )


def _K_form(X, f, pitch, size):
    K = np.array([[f / pitch, 0, (size[0] - 1) / 2], [0, f / pitch, (size[1] - 1) / 2], [0, 0, 1]])
    x = np.asarray(X) @ K.T
    return x[:, :2] / x[:, 2:]


@pytest.mark.parametrize(
    "right",
    [
        _K_form,
        lambda X, f, p, size: np.array(
            [
                [f / p * x / z + (size[0] - 1) / 2, f / p * y / z + (size[1] - 1) / 2]
                for x, y, z in X
            ]
        ),
        lambda X, f, p, size: np.column_stack(
            [
                f / p * X[:, 0] / X[:, 2] + size[0] / 2 - 0.5,
                f / p * X[:, 1] / X[:, 2] + size[1] / 2 - 0.5,
            ]
        ),
        lambda X, f, p, size: (
            f / p * np.asarray(X)[:, :2] / np.asarray(X)[:, [2]] + np.subtract(size, 1) / 2
        ).astype(np.float32),
    ],
    ids=["K matrix", "loop", "column_stack", "float32"],
)
def test_project_to_pixels_passes_right_answers_in_other_forms(right, capsys):
    assert check("project_to_pixels", right).passed is True


@pytest.mark.parametrize(
    "wrong, cause",
    [
        (
            lambda X, f, p, size: f / p * X[:, :2] / X[:, 2:3] + np.array(size) / 2,
            "half-pixel offset",
        ),
        (
            lambda X, f, p, size: (f * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2) / p,
            "added the centre before dividing by the pitch",
        ),
        (
            lambda X, f, p, size: f / p * X[:, :2] / X[:, 1:2] + (np.array(size) - 1) / 2,
            r"divided by column 1 \(Y\)",
        ),
        (
            lambda X, f, p, size: np.column_stack(
                [
                    f / p * X[:, 0] / X[:, 2] + (size[0] - 1) / 2,
                    f / p * size[1] / size[0] * X[:, 1] / X[:, 2] + (size[1] - 1) / 2,
                ]
            ),
            "scaled f_y by H / W",
        ),
        (
            lambda X, f, p, size: (
                f / p * X[:, :2] / X[:, 2:3] + (np.array([size[1], size[0]]) - 1) / 2
            ),
            "width and height swapped",
        ),
        (
            lambda X, f, p, size: (
                f / p * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2
            ).tolist(),
            "you returned a list",
        ),
        (
            lambda X, f, p, size: str(f / p * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2),
            "you returned a str",
        ),
        (
            lambda X, f, p, size: (
                f / p * X[:, :2] / np.linalg.norm(X, axis=1, keepdims=True)
                + (np.array(size) - 1) / 2
            ),
            "distance to the point",
        ),
        (
            lambda X, f, p, size: (
                (f / p * X[:, :2] / X[:, 2:3]) * [1, -1] + (np.array(size) - 1) / 2
            ),
            "flipped v",
        ),
        # round 3 of lesson 01's reviews: each of these got the generic "check each step"
        (
            lambda X, f, p, size: f / p * X[:, :2] / X[:, 2:3] + (np.array(size) + 1) / 2,
            "1-based pixels",
        ),
        (
            lambda X, f, p, size: f / p * X[:, :2] / X[:, 2:3] + [(size[0] - 1) / 2, size[1] / 2],
            "half-pixel offset in v only",
        ),
        (
            lambda X, f, p, size: f / p * X[:, :2] / X[:, 2:3] + (size[0] - 1) / 2,
            r"\(W - 1\) / 2 for both",
        ),
        (
            lambda X, f, p, size: f / p * X[:, :2] / X[:, 2:3] + np.array(size) / 2 - 1,
            "yours is W / 2 - 1",
        ),
        (
            lambda X, f, p, size: np.round(f / p * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2),
            "rounded to whole pixels",
        ),
        (
            lambda X, f, p, size: f / p * X[:, :2] / (X[:, 2:3] + f) + (np.array(size) - 1) / 2,
            "divided by Z \\+ f",
        ),
        (
            lambda X, f, p, size: f / p * X[:, :2] / X[:, 2:3] + [(size[0] - 1) / 2, 0],
            "left out c_v",
        ),
        (
            lambda X, f, p, size: (
                (f / p * X[:, :2] / X[:, 2:3]) * [-1, 1] + (np.array(size) - 1) / 2
            ),
            "negated u only",
        ),
        (
            lambda X, f, p, size: (np.asarray(X) @ _K(f, p, size).T)[:, :2],
            "did not divide by its third coordinate",
        ),
        (lambda X, f, p, size: np.asarray(X) @ _K(f, p, size).T, "homogeneous"),
        (
            lambda X, f, p, size: (lambda x: x[:, :2] / x[:, 2])(np.asarray(X) @ _K(f, p, size).T),
            "keepdims",
        ),
        (
            lambda X, f, p, size: (lambda x: x[:, :2] / x[:, 2:])(np.asarray(X) @ _K(f, p, size)),
            "X @ K.T",
        ),
        (
            lambda X, f, p, size: f / (p * 1e6) * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2,
            "micrometres",
        ),
    ],
)
def test_project_to_pixels_names_the_slip(wrong, cause):
    with pytest.raises(AssertionError, match=cause):
        check("project_to_pixels", wrong)


@pytest.mark.parametrize(
    "right",
    [
        lambda fov, size: size[0] / 2 / np.tan(np.deg2rad(fov) / 2),
        lambda fov, size: 0.5 * size[0] / np.tan(fov * np.pi / 360),
        lambda fov, size: np.asarray(
            size[0] / (2 * np.tan(np.radians(fov / 2)))
        ),  # a 0-d array is one number
        lambda fov, size: size[0] / 2 / __import__("math").tan(__import__("math").radians(fov) / 2),
    ],
    ids=["deg2rad", "pi/360", "0-d array", "math"],
)
def test_focal_length_pixels_passes_right_answers_in_other_forms(right, capsys):
    assert check("focal_length_pixels", right).passed is True


def test_focal_length_pixels_passes_a_tenth_of_a_pixel_and_names_the_slips_round_3_found(capsys):
    assert check(
        "focal_length_pixels", lambda fov, size: round(size[0] / 2 / np.tan(np.radians(fov) / 2), 1)
    ).passed
    for wrong, cause in (
        (lambda fov, size: size[0] / 2 * np.tan(np.radians(fov) / 2), "you multiplied by tan"),
        (lambda fov, size: size[0] / 2 / np.tan(np.radians(fov)), "use half the field of view"),
        (lambda fov, size: -size[0] / 2 / np.tan(np.radians(fov) / 2), "a sign flip"),
        (lambda fov, size: int(size[0] / 2 / np.tan(np.radians(fov) / 2)), "rounded f_x"),
        (lambda fov, size: (size[0] - 1) / 2 / np.tan(np.radians(fov) / 2), "spans all W pixels"),
    ):
        with pytest.raises(AssertionError, match=cause):
            check("focal_length_pixels", wrong)


def test_best_pinhole_exposure_names_the_unit_of_time():
    for wrong, cause in (
        (lambda f, lam, t, N: 1e3 * t * f / (2.44 * lam * N**2), "milliseconds"),
        (lambda f, lam, t, N: t * f / (2.44 * lam * N**2) / 60, "minutes"),
        (
            lambda f, lam, t, N: t * (np.sqrt(f) / np.sqrt(2.44 * lam * f) / N) ** 2,
            r"you used sqrt\(f\)",
        ),
    ):
        with pytest.raises(AssertionError, match=cause) as info:
            check("best_pinhole_exposure", wrong)
        assert "the answer are in metres" not in str(info.value)


def test_focal_length_pixels_rejects_a_one_element_list_naming_the_fix():
    with pytest.raises(
        AssertionError, match=r"you returned a list of shape \(1,\); return one number"
    ):
        check("focal_length_pixels", lambda fov, size: [size[0] / 2 / np.tan(np.radians(fov) / 2)])


def test_best_pinhole_exposure_accepts_a_numerical_best_hole_and_rejects_a_few_percent_off(capsys):
    from scipy.optimize import minimize_scalar

    def numerical(f, lam, t, N):
        d = minimize_scalar(
            lambda d: d + 2.44 * lam * f / d, bounds=(1e-6, 1e-2), method="bounded"
        ).x
        return t * (f / d / N) ** 2

    def scipy_defaults(
        f, lam, t, N
    ):  # the route a reviewer took: 1.08 % off the time, rejected at rtol 1 %
        d = minimize_scalar(
            lambda x: x + 2.44 * lam * f / x, bounds=(1e-5, 1e-3), method="bounded"
        ).x
        return t * (f / d / N) ** 2

    assert check("best_pinhole_exposure", numerical).passed is True
    assert check("best_pinhole_exposure", scipy_defaults).passed is True
    assert (
        check("best_pinhole_exposure", lambda f, lam, t, N: t * f / (2.44 * lam * N**2)).passed
        is True
    )
    with pytest.raises(
        AssertionError, match="wrong answer"
    ):  # a hole 4.7 % off d*: its blur 0.1 % over the least
        check("best_pinhole_exposure", lambda f, lam, t, N: 1.10 * t * f / (2.44 * lam * N**2))


@pytest.mark.parametrize(
    "name", ["best_pinhole_diameter", "focal_length_pixels", "best_pinhole_exposure"]
)
def test_a_number_written_as_a_string_is_rejected(name):
    reference = EXERCISES[name].reference
    with pytest.raises(AssertionError, match="you returned a str, which is not numbers"):
        check(name, lambda *args: f"{reference(*args):.6g}")


@pytest.mark.parametrize(
    "wrap, phrase",
    [
        (lambda a: (a,), "a trailing comma, `return x,`, makes a tuple"),
        (lambda a: [a], "brackets, `[x]`, make a list"),
    ],
    ids=["tuple", "list"],
)
def test_an_array_wrapped_in_a_tuple_or_list_is_named(wrap, phrase):
    from camlab.exercises import type_problem

    answer = np.array([2.5, 4.25, 1.0])
    assert phrase in type_problem(wrap(answer), answer, ndarray_only=True)


def test_an_unfilled_np_empty_answer_fails_instead_of_passing_on_freed_memory():
    """np.empty(3) would often hold the reference answer the check has just computed and freed."""

    def lift(p):
        out = np.empty(3)
        out[:2] = p  # w never set
        return out

    with pytest.raises(
        AssertionError,
        match=r"w is NaN and x and y are right: .*an array made with np\.empty\(3\) kept whatever",
    ):
        check("lift", lift)


def test_rq_mismatch_names_matrix_row_column_and_no_negative_zero():
    """Final review of lesson 04: an index into the (K, R) pair was labelled (row, column, channel)."""
    from camlab.exercises.projective_camera.rq import _rq_forced_rotation

    with pytest.raises(AssertionError, match=r"\(matrix, row, column\)") as info:
        check("rq_decomposition", _rq_forced_rotation)
    assert "channel" not in str(info.value) and "R must be" not in str(info.value)
    assert "a reflection" in str(info.value)


def test_lift_names_a_notebook_variable_read_instead_of_p(monkeypatch):
    """A lift that reads a variable of the notebook (the worked example's `points`) instead of its argument gets
    a hint naming that variable; the in-place hint for a (2,) point speaks of p, not of batch code."""
    import __main__

    monkeypatch.setattr(__main__, "points", np.array([[319.5, 239.5], [0.0, 0.0]]), raising=False)
    with pytest.raises(AssertionError, match=r"those of the notebook's `points\[0\]`, not of p"):
        check("lift", lambda p: np.append(__main__.points[0], 1.0))

    def lift_in_place(p):
        out = np.append(p, 1.0)
        p[0] = 99.0
        return out

    with pytest.raises(AssertionError, match=r"changed its input `p` in place") as caught:
        check("lift", lift_in_place)
    assert (
        "`p[1] = -p[1]`" in str(caught.value)
        and "x *= L" not in str(caught.value)
        and "[:, 0]" not in str(caught.value)
    )


def _dlt_refined_in_raw_coordinates(X, uv, method="lm"):
    """A normalised DLT, then scipy's least squares on P's 12 raw entries (metres and pixels), as students write it."""
    from scipy.optimize import least_squares

    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)
    P0 = __import__("camlab").camera.estimate_projection_matrix(X, uv)
    Xh = np.column_stack([X, np.ones(len(X))])

    def residuals(p):
        x = Xh @ p.reshape(3, 4).T
        return (x[:, :2] / x[:, 2:] - uv).ravel()

    fit = least_squares(
        residuals,
        (P0 / np.linalg.norm(P0)).ravel(),
        method=method,
        xtol=1e-15,
        ftol=1e-15,
        gtol=1e-15,
    )
    return fit.x.reshape(3, 4)


def test_estimate_projection_matrix_passes_an_lm_refinement_in_raw_coordinates(capsys):
    # The prompt says an LM refinement passes: LM on P's raw entries reaches the maximum-likelihood camera in every
    # frame, though its path moves it by up to 0.06 px between units (reviewer T, round 4).
    assert check("estimate_projection_matrix", _dlt_refined_in_raw_coordinates).passed is True


def test_estimate_projection_matrix_names_a_refinement_that_stalls_in_other_units():
    # TRF on raw entries never leaves its start in millimetres: the hint names the refinement, not "no normalisation".
    with pytest.raises(AssertionError) as info:
        check(
            "estimate_projection_matrix",
            lambda X, uv: _dlt_refined_in_raw_coordinates(X, uv, method="trf"),
        )
    assert "you refined it" in str(info.value) and "Gold Standard" in str(info.value)
    assert "no normalisation" not in str(info.value)


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_a_printed_solution_never_ends_in_an_empty_reference_line(name):
    """solution() names what a private reference computes from its docstring's first line: it must have one."""
    from camlab.exercises import solution_source

    text = solution_source(name)
    assert not text.rstrip().endswith(("tested reference:", "tested reference.", "#")), text[-200:]


@pytest.mark.parametrize(
    "wrong, cause",
    [
        (
            lambda f, lam, t, N: -t * f / (2.44 * lam * N**2),
            "a sign flip: an exposure time is a positive number",
        ),
        (
            lambda f, lam, t, N: -t * f / (2 * lam * N**2),
            "an exposure time is a positive number of seconds",
        ),
        (lambda f, lam, t, N: float("nan"), "you returned NaN"),
        (lambda f, lam, t, N: 0.0, "you returned 0 s"),
        (lambda f, lam, t, N: float("inf"), "you returned infinity"),
    ],
    ids=["negative", "negative-and-wrong", "nan", "zero", "inf"],
)
def test_best_pinhole_exposure_explains_a_negative_nan_or_zero_time_instead_of_crashing(
    wrong, cause
):
    """A sign slip once crashed the diagnosis (log10 of a negative ratio, then round(nan)); each such answer now
    gets a hint of its own (a sign flip is no square root of a negative number)."""
    with pytest.raises(AssertionError, match=rf"likely cause: {cause}"):
        check("best_pinhole_exposure", wrong)


def test_no_hint_cites_a_cell_number():
    """Cells move when a lesson is edited (round 5 of lesson 03: 'cell 11's formula' pointed at a plot): hints
    name the section instead."""
    import pathlib
    import re

    import camlab.exercises as package

    for path in pathlib.Path(package.__file__).parent.rglob("*.py"):
        cited = re.findall(r"\bcells? \d+", path.read_text(encoding="utf-8"))
        assert not cited, f"{path.name} cites {cited}"


def test_read_noise_with_the_quantisation_variance_removed_passes_too(capsys):
    """Lesson 03, exercise 3's prompt: subtracting 1/12 DN^2 (as EMVA 1288 does) moves the read noise by under 2 %."""
    from camlab.exercises import sensor_noise

    for darks, _flats in sensor_noise._cases():
        d = np.asarray(darks[0], dtype=float) - np.asarray(darks[1], dtype=float)
        var = np.var(d) / 2
        assert 0 < np.sqrt(var) / np.sqrt(var - 1 / 12) - 1 < 0.02

    def emva(darks, flats):
        g, _ = sensor_noise.gain_and_read_noise(darks, flats)
        d1, d2 = (np.asarray(d, dtype=float) for d in darks)
        return g, g * np.sqrt(np.var(d1 - d2) / 2 - 1 / 12)

    assert check("gain_and_read_noise", emva).passed is True


def test_quantize_image_accepts_a_loop_over_the_rows_and_columns_of_a_grey_image(capsys):
    """Lesson 03, exercise 2's prompt says a grey (H, W) image: a solution that unpacks H, W must pass."""

    def loop(image, bits):
        H, W = image.shape
        out = np.zeros((H, W), np.uint8 if bits <= 8 else np.uint16)
        for v in range(H):
            for u in range(W):
                out[v, u] = min(max(round(image[v, u] * (2**bits - 1)), 0), 2**bits - 1)
        return out

    assert check("quantize_image", loop).passed is True


def test_quantize_image_names_a_colour_axis_unpacked_from_a_grey_image():
    def colour(image, bits):
        H, W, C = image.shape
        return np.zeros((H, W), np.uint8)

    with pytest.raises(
        AssertionError, match=r"likely cause: the test image has shape \(3, 4\), a grey"
    ):
        check("quantize_image", colour)


def test_alias_frequency_accepts_other_ways_to_fold(capsys):
    """Lesson 03, exercise 5: np.where on f % 1, or the distance to the nearest whole cycle, are right too."""

    def where(f):
        a = np.mod(f, 1)
        return np.where(a > 0.5, 1 - a, a)

    assert check("alias_frequency", where).passed is True
    assert check("alias_frequency", lambda f: np.abs(f - np.round(f))).passed is True


# lesson 11: right answers in other valid forms pass


def test_eight_point_accepts_rms_normalisation(capsys):
    """Scaling to an RMS distance sqrt(2) (not the mean) is Hartley's algorithm too: F moves by ~4e-5."""
    from camlab.exercises.stereo_rectification.eight_point import _rms_normalised

    assert check("eight_point", _rms_normalised).passed


def test_decompose_essential_accepts_any_order_and_disparity_to_depth_any_float(capsys):
    from camlab.exercises.stereo_rectification.essential import decompose_essential

    reordered = lambda E: tuple(a[[2, 0, 3, 1]] for a in decompose_essential(E))  # noqa: E731
    assert check("decompose_essential", reordered).passed
    assert check(
        "disparity_to_depth", lambda d, f, B, o: f * B / (np.asarray(d, np.float32) + o)
    ).passed


def test_jupyter_shows_a_wrong_answer_as_its_message_not_camlab_source():
    """IPython renders CheckFailed through _render_traceback_: the message, no frames of camlab's
    check machinery; when the student's function crashed, the student's own frames stay."""
    from camlab.exercises import check_lift
    from camlab.exercises._core import CheckFailed

    def lift(p):
        return np.c_[p, np.zeros(len(p))]

    with pytest.raises(CheckFailed) as wrong:
        check_lift(lift)
    shown = "\n".join(wrong.value._render_traceback_())
    assert shown.startswith("CheckFailed: lift: wrong answer") and "likely cause" in shown
    assert "_core.py" not in shown and "camlab" + "/exercises" not in shown

    def crashing_lift(p):
        return p[:, 5]

    with pytest.raises(CheckFailed) as crashed:
        check_lift(crashing_lift)
    shown = "\n".join(crashed.value._render_traceback_())
    assert "in crashing_lift" in shown and "return p[:, 5]" in shown and "IndexError" in shown
    assert "_core.py" not in shown and "_timer.py" not in shown


@pytest.mark.parametrize(
    "answer",
    [
        lambda H, C: np.linalg.solve(H.T, C) @ np.linalg.inv(H),  # solve instead of inv
        lambda H, C: -2.0 * np.linalg.inv(H).T @ C @ np.linalg.inv(H),  # any non-zero scale
        lambda H, C: (lambda G: G / G[2, 2])(np.linalg.inv(H).T @ C @ np.linalg.inv(H)),
        lambda H, C: (lambda A: A.T @ C @ A)(np.linalg.inv(H / H[2, 2])),  # H rescaled first
    ],
)
def test_map_conic_accepts_right_answers_in_other_forms(answer, capsys):
    assert check("map_conic", answer).passed


def test_map_conic_names_a_transposed_H_as_the_transpose_on_the_wrong_side():
    # x @ H for H @ x in the student's head: they move the conic by H.T, i.e. inv(H) @ C @ inv(H).T
    with pytest.raises(AssertionError, match="transpose is on the wrong factor"):
        check("map_conic", lambda H, C: np.linalg.inv(H.T).T @ C @ np.linalg.inv(H.T))


def test_project_to_pixels_passes_a_float32_projection_and_keeps_the_broadcasting_hint_for_its_slip():
    def float32(X, f, pitch, size):
        X = np.asarray(X, dtype=np.float32)
        return (
            np.float32(f / pitch) * X[:, :2] / X[:, 2:3] + (np.array(size, np.float32) - 1) / 2
        ).astype(float)

    check(
        "project_to_pixels", float32
    )  # float32 arithmetic returned as float64: within a thousandth of a pixel
    with pytest.raises(AssertionError) as info:
        check(
            "project_to_pixels",
            lambda X, f, p, size: f / p * X[:, :2] / X[:, 2] + (np.array(size) - 1) / 2,
        )
    assert "test input 2 of 3" in str(info.value) and "broadcasting slip" in str(info.value)
    with pytest.raises(AssertionError) as info:
        check(
            "project_to_pixels",
            lambda X, f, p, size: f / p * X[:, :2] / X[:, 2:3] + (np.array(size) - 1) / 2 + 0.01,
        )
    assert "broadcasting" not in str(info.value)


def test_focal_length_pixels_rejects_an_integer_half_width_on_an_odd_width():
    with pytest.raises(AssertionError) as info:
        check("focal_length_pixels", lambda fov, size: size[0] // 2 / np.tan(np.radians(fov) / 2))
    assert "641 // 2 is 320" in str(info.value)


def _conic_rows_for_test(L, M):
    (l1, l2, l3), (m1, m2, m3) = np.asarray(L, float).T, np.asarray(M, float).T
    return np.stack(
        [
            l1 * m1,
            (l1 * m2 + l2 * m1) / 2,
            l2 * m2,
            (l1 * m3 + l3 * m1) / 2,
            (l2 * m3 + l3 * m2) / 2,
            l3 * m3,
        ],
        1,
    )


def _conic_from_vector(x):
    a, b, c, d, e, f = x
    return np.array([[a, b / 2, d / 2], [b / 2, c, e / 2], [d / 2, e / 2, f]])


def test_dual_conic_accepts_the_smallest_eigenvector_of_the_normal_equations(capsys):
    """eigh(A^T A) squares the rows' condition number (about 1e-4 off on pixel lines) but is a sound method."""

    def by_eigh(L, M):
        A = _conic_rows_for_test(L, M)
        return _conic_from_vector(np.linalg.eigh(A.T @ A)[1][:, 0])

    assert check("dual_conic_from_orthogonal_lines", by_eigh)


def test_order_corners_rejects_the_sum_and_difference_shortcut_on_a_page_in_perspective():
    def shortcut(c):
        q = np.asarray(c, float)
        s, d = q.sum(1), q[:, 1] - q[:, 0]
        return q[[s.argmin(), d.argmin(), s.argmax(), d.argmax()]]

    with pytest.raises(AssertionError, match="u \\+ v / v - u shortcut"):
        check("order_corners", shortcut)


@pytest.mark.parametrize(
    "answer",
    [
        lambda H: np.cross(H[:, 0], H[:, 1]),  # the two ground vanishing points joined
        lambda H: np.linalg.solve(H.T, [0.0, 0.0, 1.0]),
        lambda H: -3.0 * np.linalg.inv(H)[2],  # inv(H)'s third row, any scale
    ],
)
def test_horizon_line_accepts_right_answers_in_other_forms(answer, capsys):
    assert check("horizon_line", answer).passed
    assert "H[:, 0] x H[:, 1] is the same line" in capsys.readouterr().out


@pytest.mark.parametrize(
    "name, answer, phrase",
    [
        (
            "intersect_lines",
            lambda l1, l2: np.append(np.linalg.solve([l1[:2], l2[:2]], [-l1[2], -l2[2]]), 1.0),
            "parallel lines",
        ),
        (
            "vanishing_point",
            lambda s: np.append(
                np.linalg.solve(
                    [
                        np.cross([*s[0, 0], 1], [*s[0, 1], 1])[:2],
                        np.cross([*s[1, 0], 1], [*s[1, 1], 1])[:2],
                    ],
                    [
                        -np.cross([*s[0, 0], 1], [*s[0, 1], 1])[2],
                        -np.cross([*s[1, 0], 1], [*s[1, 1], 1])[2],
                    ],
                ),
                1.0,
            ),
            "parallel lines",
        ),
    ],
)
def test_projective_plane_checks_name_a_euclidean_solve_on_parallel_lines(name, answer, phrase):
    with pytest.raises(AssertionError, match=phrase):
        check(name, answer)


@pytest.mark.parametrize("target", ["half", "box"])
def test_eight_point_accepts_other_similarity_normalisations(target, capsys):
    """Mean distance 0.5 or the box [-1, 1], undone correctly, pass (the reference uses sqrt(2))."""

    def eight_point(x1, x2):
        def normaliser(p):
            if target == "box":
                lo, hi = p.min(axis=0), p.max(axis=0)
                c, s = (lo + hi) / 2, 2 / (hi - lo)
                return np.array([[s[0], 0, -s[0] * c[0]], [0, s[1], -s[1] * c[1]], [0, 0, 1]])
            c = p.mean(axis=0)
            s = 0.5 / np.mean(np.linalg.norm(p - c, axis=1))
            return np.array([[s, 0, -s * c[0]], [0, s, -s * c[1]], [0, 0, 1]])

        T1, T2 = normaliser(x1), normaliser(x2)
        a = np.c_[x1, np.ones(len(x1))] @ T1.T
        b = np.c_[x2, np.ones(len(x2))] @ T2.T
        A = np.column_stack([b[:, [0]] * a, b[:, [1]] * a, a])
        U, S, Vt = np.linalg.svd(np.linalg.svd(A)[2][-1].reshape(3, 3))
        return T2.T @ U @ np.diag([S[0], S[1], 0.0]) @ Vt @ T1

    assert check("eight_point", eight_point).passed


def test_triangulate_point_accepts_the_inhomogeneous_least_squares_form(capsys):
    """X_h = (X, 1) and least squares on the 4 x 3 system: H&Z's inhomogeneous method, as valid."""

    def triangulate_point(P1, P2, x1, x2):
        P1, P2 = np.asarray(P1), np.asarray(P2)
        A = np.array(
            [
                x1[0] * P1[2] - P1[0],
                x1[1] * P1[2] - P1[1],
                x2[0] * P2[2] - P2[0],
                x2[1] * P2[2] - P2[1],
            ]
        )
        A /= np.linalg.norm(A, axis=1, keepdims=True)
        return np.linalg.lstsq(A[:, :3], -A[:, 3], rcond=None)[0]

    assert check("triangulate_point", triangulate_point).passed


@pytest.mark.parametrize("take", [slice(None), slice(0, 2)])
def test_rq_decomposition_names_raw_rqdecomp3x3_output(take):
    import cv2

    with pytest.raises(AssertionError, match=r"likely cause: you returned .* of cv2.RQDecomp3x3"):
        check("rq_decomposition", lambda M: cv2.RQDecomp3x3(M)[take])


def test_rq_decomposition_names_rqdecomp3x3_sign_in_k33():
    import cv2

    with pytest.raises(AssertionError, match=r"likely cause: This is what cv2.RQDecomp3x3 returns"):
        check("rq_decomposition", lambda M: cv2.RQDecomp3x3(M)[1:3])


@pytest.mark.parametrize("axis", [0, 1])
def test_project_points_half_pixel_on_one_axis_named(axis):
    from camlab import camera as cm

    def project_points(P, X):
        uv = cm.project_points(P, X)
        uv[:, axis] += 0.5
        return uv

    with pytest.raises(AssertionError, match=r"likely cause: every [uv] is off by \+0.5 px while"):
        check("project_points", project_points)


def test_a_def_with_the_wrong_parameters_is_named_only_when_the_call_itself_fails():
    def two(img, X):
        return None

    with pytest.raises(AssertionError) as info:
        check("read_and_turn", two)
    assert "calls your function as read_and_turn(img, X, A), 3 arguments" in str(info.value)

    def inner_slip(
        img, X, A
    ):  # a TypeError from a call inside the student's code is not about their def
        return np.linalg.inv(A, X)

    with pytest.raises(AssertionError) as info:
        check("read_and_turn", inner_slip)
    assert "wrong number of parameters" not in str(info.value)


def test_int_of_an_array_gets_a_hint_in_every_lesson():
    def centred(X):
        return X - int(X.mean(axis=0))

    hint = exercises._core._exception_hint(_raised(centred, np.ones((3, 2))))
    assert "int() or float() of an array" in hint


def _raised(function, *args):
    try:
        function(*args)
    except Exception as exc:  # noqa: BLE001 - the error is what the test inspects
        return exc
    raise AssertionError("expected an error")


def test_a_diagnosis_that_fails_on_an_unforeseen_answer_still_reports_a_wrong_answer(monkeypatch):
    """A (1,) array where a number belongs once made a diagnosis raise TypeError out of the check."""
    import dataclasses

    from camlab.exercises import _core

    def broken(args, got, expected):
        raise TypeError("only 0-dimensional arrays can be converted to Python scalars")

    exercise = dataclasses.replace(_core.EXERCISES["expected_rms"], diagnose=broken)
    monkeypatch.setitem(_core.EXERCISES, "expected_rms", exercise)
    with pytest.raises(_core.CheckFailed, match="could not diagnose this answer"):
        _core.check("expected_rms", lambda sigma, *counts: np.array([2 * sigma]))


def _read_and_turn_about(centre):
    """A read_and_turn whose centre is right but whose turn uses ``centre(img, c)``."""

    def answer(img, X, A):
        H, W = img.shape
        c = np.array([(W - 1) / 2, (H - 1) / 2])
        values = img[np.rint(X[:, 1]).astype(int), np.rint(X[:, 0]).astype(int)]
        w = np.asarray(centre(img, c), dtype=float)
        return c, values, (X - w) @ A.T + w

    return answer


def test_read_and_turn_names_a_wrong_turn_centre_only_when_it_is_the_one_fit():
    # about the swapped centre (1.5, 2.5) of the 6 x 4 image: named as swapped, never as another centre
    with pytest.raises(AssertionError) as info:
        check("read_and_turn", _read_and_turn_about(lambda img, c: c[::-1]))
    message = str(info.value)
    assert (
        "you moved the points about [1.5, 2.5], not about the centre c = [2.5, 1.5]" in message
    ), message
    assert "width and height swapped" in message, message
    assert "counted from 1" not in message, message


def test_read_and_turn_names_the_notebooks_W_H_and_c(monkeypatch):
    main = sys.modules["__main__"]
    monkeypatch.setattr(main, "W", 640, raising=False)
    monkeypatch.setattr(main, "H", 480, raising=False)
    monkeypatch.setattr(main, "c", np.array([1.5, 1.0]), raising=False)

    def stale(W, H, c):
        def answer(img, X, A):
            centre = np.array([(W - 1) / 2, (H - 1) / 2]) if c is None else c
            values = img[np.rint(X[:, 1]).astype(int), np.rint(X[:, 0]).astype(int)]
            return centre, values, (X - centre) @ A.T + centre

        return answer

    with pytest.raises(AssertionError) as info:
        check("read_and_turn", stale(640, 480, None))
    assert (
        "(319.5, 239.5) is the centre of a 640 x 480 image: your function reads the notebook's W, H"
        in str(info.value)
    )
    with pytest.raises(AssertionError) as info:
        check("read_and_turn", stale(0, 0, main.c))
    assert "(1.5, 1) is the notebook's variable c (section 3.3)" in str(info.value)


def test_the_lift_solution_names_camlabs_tested_route():
    # lesson 00 tells students the teaching solution's last line names camlab.to_homogeneous
    assert (
        solution_source("lift")
        .rstrip()
        .endswith("camlab.to_homogeneous (read it with camlab.to_homogeneous??)")
    )


def _cr_brackets(points):
    """H&Z's brackets: det [o x_i x_j] for a point o off the line; each x_i's scale cancels."""
    x = np.asarray(points, dtype=float)
    o = np.cross(x[0], x[3])  # the line through A and D, read as a point: off the line (l . l > 0)
    b = lambda i, j: np.linalg.det(np.array([o, x[i], x[j]]))  # noqa: E731
    return b(0, 2) * b(1, 3) / (b(1, 2) * b(0, 3))


def _cr_unit_direction(points):
    p = np.asarray(points, dtype=float)
    xy = p[:, :2] / p[:, 2:]
    d = (xy[1] - xy[0]) / np.linalg.norm(xy[1] - xy[0])
    t = xy @ d
    return float((t[2] - t[0]) * (t[3] - t[1]) / ((t[2] - t[1]) * (t[3] - t[0])))


def _cr_signed_norms(points):
    p = np.asarray(points, dtype=float)
    xy = p[:, :2] / p[:, 2:]
    d = xy[3] - xy[0]

    def s(i, j):
        v = xy[j] - xy[i]
        return np.sign(v @ d) * np.linalg.norm(v)

    return s(0, 2) * s(1, 3) / (s(1, 2) * s(0, 3))


def _cr_distance_from_a(points):
    """The slip: positions as unsigned distances from A, right only while A is an end point."""
    xy = points[:, :2] / points[:, 2:]
    a, b, c, d = np.linalg.norm(xy - xy[0], axis=1)
    return (c - a) * (d - b) / ((c - b) * (d - a))


@pytest.mark.parametrize("right", [_cr_brackets, _cr_unit_direction, _cr_signed_norms])
def test_cross_ratio_passes_right_answers_in_other_forms(right, capsys):
    assert check("cross_ratio", right).passed


@pytest.mark.parametrize(
    ("wrong", "cause"),
    [
        (lambda p: 1.0 - 1.0 / _cr_brackets(p), "Hartley & Zisserman's Cross"),
        (lambda p: abs(_cr_brackets(p)), "unsigned lengths"),
        (
            lambda p: _cr_distance_from_a(np.asarray(p, dtype=float)),
            "unsigned distance from A",
        ),
        (
            lambda p: _cr_signed_norms(np.c_[np.asarray(p)[:, :2], np.ones(4)]),
            "without dividing by w",
        ),
        (lambda p: _cr_unit_direction(np.asarray(p)[[1, 0, 2, 3]]), "A and B"),
        (lambda p: _cr_unit_direction(np.asarray(p)[[0, 2, 1, 3]]), "another order"),
        (lambda p: np.array([_cr_brackets(p)]), "holding one number"),
    ],
)
def test_cross_ratio_names_the_typical_slips(wrong, cause):
    with pytest.raises(AssertionError, match=cause):
        check("cross_ratio", wrong)


def _read_and_turn_with(centre, turn):
    """A read_and_turn whose centre and turn are given; the values are read the right way."""

    def answer(img, X, A):
        c = np.asarray(centre(img), dtype=float)
        values = img[np.rint(X[:, 1]).astype(int), np.rint(X[:, 0]).astype(int)]
        return c, values, turn(X, c, np.asarray(A))

    return answer


def _right_centre(img):
    return np.array([(img.shape[1] - 1) / 2, (img.shape[0] - 1) / 2])


@pytest.mark.parametrize(
    "wrong, cause",
    [
        (lambda p: p + np.array([0.0, 0.0, 1.0]), "p has 2 entries and your array 3"),
        (lambda p: p * np.ones(3), "p has 2 entries and your array 3"),
    ],
    ids=["p + [0, 0, 1]", "p * ones(3)"],
)
def test_lift_names_arithmetic_that_cannot_add_a_coordinate(wrong, cause):
    """A9's first wrong attempt: + or * of the (2,) point with a (3,) array, not a division by X[:, 2]."""
    with pytest.raises(AssertionError) as info:
        check("lift", wrong)
    message = str(info.value)
    assert cause in message and "np.append(p, 1.0)" in message, message
    assert "X[:, 2]" not in message, message


@pytest.mark.parametrize(
    "turn, cause",
    [
        (
            lambda X, c, A: (X - c) * A + c,
            "* multiplies entry by entry, and X - c, shape (3, 2), and A",
        ),
        (lambda X, c, A: (X - c) * np.diag(A) + c, "scales u and v by A's diagonal alone"),
        (lambda X, c, A: (X - c) * A[0, 0] + c, "* by one entry of A"),
    ],
    ids=["* A (raises)", "* diag(A)", "* A[0, 0]"],
)
def test_read_and_turn_names_star_for_matrix_product(turn, cause):
    with pytest.raises(AssertionError) as info:
        check("read_and_turn", _read_and_turn_with(_right_centre, turn))
    message = str(info.value)
    assert cause in message and "(X - c) @ A.T + c" in message, message
    assert "X[:, 2]" not in message, message


def test_read_and_turn_names_the_precedence_slip_in_the_centre():
    answer = _read_and_turn_with(
        lambda img: np.array(img.shape[::-1]) - 1 / 2, lambda X, c, A: (X - c) @ A.T + c
    )
    with pytest.raises(AssertionError) as info:
        check("read_and_turn", answer)
    assert "/ binds before -" in str(info.value), str(info.value)


@pytest.mark.parametrize(
    "left, right, named, flat",
    [
        ((6, 2), (6,), "(6, 2) and (6,)", True),
        ((3, 2), (2, 2), "(3, 2) and (2, 2)", False),
        ((2,), (3,), "(2,) and (3,)", False),
        ((3, 2), (4,), "(3, 2) and (4,)", False),
    ],
)
def test_the_shared_broadcasting_hint_names_the_two_shapes(left, right, named, flat):
    """The fallback names the shapes numpy could not pair; only an (N,) beside an (N, k) gets X[:, 2:3]."""
    hint = exercises._core._exception_hint(
        _raised(lambda a, b: a / b, np.ones(left), np.ones(right))
    )
    assert "broadcasting slip" in hint and named in hint, hint
    assert ("X[:, 2:3]" in hint) == flat, hint


def test_got_and_expected_print_with_the_same_decimals():
    with pytest.raises(AssertionError) as info:
        check("lift", lambda p: np.r_[p, 1.0] / 1000)
    message = str(info.value)
    assert "got      [0.00250, 0.00425, 0.00100]" in message, message
    assert "expected [2.50000, 4.25000, 1.00000]" in message, message


def _rank3_via(layout):
    """A student's Tomasi-Kanade reprojection with another (valid) measurement-matrix layout."""

    def student(tracks):
        m, N, _ = tracks.shape
        t = tracks.mean(axis=1, keepdims=True)
        if layout == "stacked":  # all u rows, then all v rows
            W = (tracks - t).transpose(2, 0, 1).reshape(2 * m, N)
        else:  # the transpose, N x 2m
            W = (tracks - t).transpose(1, 0, 2).reshape(N, 2 * m)
        U, s, Vt = np.linalg.svd(W, full_matrices=True)
        W3 = U[:, :3] @ np.diag(s[:3]) @ Vt[:3]
        if layout == "stacked":
            return W3.reshape(2, m, N).transpose(1, 2, 0) + t
        return W3.reshape(N, m, 2).transpose(1, 0, 2) + t

    return student


@pytest.mark.parametrize("layout", ["stacked", "transposed"])
def test_reproject_rank3_accepts_any_layout_of_the_measurement_matrix(layout, capsys):
    assert check("reproject_rank3", _rank3_via(layout)).passed is True


@pytest.mark.parametrize(
    "right",
    [
        lambda h: h[:, :2] / h[:, 2, None],
        lambda h: h[:, :2] / h[:, [2]],
        lambda h: (h[:, :2].T / h[:, 2]).T,
        lambda h: np.array([row[:2] / row[2] for row in h]),
        lambda h: np.array(
            [[a / w, b / w] for a, b, w in h.tolist()]
        ),  # Python floats: 3.0 / 0.0 raises
    ],
    ids=["None", "list index", "transposed twice", "numpy loop", "python loop"],
)
def test_divide_by_w_passes_right_answers_in_other_forms(right, capsys):
    assert check("divide_by_w", right).passed is True


def test_divide_by_w_names_the_flat_w_on_two_points_once_three_points_are_worked_round():
    """N = 3 raises for the flat w; a student who special-cases it is caught silently wrong on N = 2."""
    with pytest.raises(
        AssertionError, match=r"test input 2 of 3(.|\n)*flat h\[:, 2\](.|\n)*keep w a column"
    ):
        check("divide_by_w", lambda h: h[:, :2] / (h[:, 2] if len(h) != 3 else h[:, 2:]))


def test_divide_by_w_in_place_hint_suggests_the_right_division_not_one_w_for_all_rows():
    """The in-place hint's fix must not be a mistake the same check rejects (h / h[2, 2]: one w for all)."""

    def in_place(h):
        h /= h[:, 2:]
        return h[:, :2]

    with pytest.raises(AssertionError, match=r"changed its input `h` in place") as info:
        check("divide_by_w", in_place)
    message = str(info.value)
    assert "`h[:, :2] / h[:, 2:]`" in message and "h[2, 2]" not in message


def test_divide_by_w_w_zero_message_names_the_further_test_and_opencvs_function():
    cv2 = pytest.importorskip("cv2")
    with pytest.raises(AssertionError) as info:
        check("divide_by_w", lambda h: cv2.convertPointsFromHomogeneous(h).reshape(-1, 2))
    message = str(info.value)
    assert (
        "correct on all" not in message
        and "the test with a row of w = 0 (a direction: the prompt asks for inf or nan there)"
        in message
    )
    assert "cv2.convertPointsFromHomogeneous" in message and "left undivided" in message
    with pytest.raises(
        AssertionError, match=r"OpenCV's layout for point lists(.|\n)*reshape\(-1, 2\)"
    ):
        check("divide_by_w", lambda h: cv2.convertPointsFromHomogeneous(h))


def test_read_and_turn_names_a_wrong_centre_once_and_the_transposed_turn():
    """Centre (W/2, H/2) and X @ A: the centre's cause is printed once; the turn names X @ A, not the centre again."""
    from camlab.exercises.start_here.conventions import read_and_turn

    def two_slips(img, X, A):
        H, W = img.shape
        c = np.array([W / 2, H / 2])
        return c, read_and_turn(img, X, A)[1], (X - c) @ A + c

    with pytest.raises(AssertionError) as info:
        check("read_and_turn", two_slips)
    message = str(info.value)
    assert message.count("pixel centres sit at whole numbers") == 1
    assert "fix c first" in message and "X @ A applies A's transpose" in message


def test_read_and_turn_in_place_hint_uses_the_exercises_own_names():
    from camlab.exercises.start_here.conventions import read_and_turn

    def shifts_X(img, X, A):
        answer = read_and_turn(img, X, A)
        X -= 1.0
        return answer

    with pytest.raises(AssertionError, match=r"changed its input `X` in place") as info:
        check("read_and_turn", shifts_X)
    assert "`X -= c`" in str(info.value) and "L`" not in str(info.value)


def test_read_and_turn_rejects_lists_as_lift_and_divide_by_w_do():
    def as_lists(img, X, A):
        from camlab.exercises.start_here.conventions import read_and_turn

        c, values, turned = read_and_turn(img, X, A)
        return list(c), values.tolist(), turned.tolist()

    with pytest.raises(
        AssertionError,
        match=r"the centre c came back as a list(.|\n)*the values came back as a list",
    ):
        check("read_and_turn", as_lists)
    for name, answer in (
        ("lift", lambda p: [p[0], p[1], 1.0]),
        ("divide_by_w", lambda h: (h[:, :2] / h[:, 2:]).tolist()),
    ):
        with pytest.raises(AssertionError, match="you returned a list"):
            check(name, answer)


def test_affine_rectification_solution_warps_to_a_usable_size():
    """The teaching H_P (l3 = 1) keeps the facade's size: not the ~1e-15 dot that raw cross products give."""
    from camlab import scenes
    from camlab.exercises.perspective_correction.affine import affine_rectification
    from camlab.projective import map_points

    corners = scenes.sample_photo("facade").corners
    H_P = affine_rectification(corners)
    assert H_P[2, 2] == 1.0
    par = map_points(H_P, corners)
    width = np.linalg.norm(par[1] - par[0])
    assert 100 < width < 2000 and np.allclose(par[1] - par[0], par[2] - par[3])


def test_affine_rectification_l_divided_by_l1_is_named():
    """Dividing l by l1, which is 0 for a horizontal vanishing line, gives inf: the hint says so."""
    from camlab.exercises.perspective_correction.affine import affine_rectification

    def by_l1(corners):
        H = affine_rectification(corners)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.array([H[0], H[1], H[2] / H[2, 0]])

    with pytest.raises(AssertionError, match="not by l1 or l2"):
        check("affine_rectification", by_l1)


def test_rectangle_homography_from_reversed_corners_is_named_mirrored():
    """Corners taken in reverse (counter-clockwise) order: the hint says the result is mirrored."""
    from camlab.exercises.perspective_correction.rectangle import rectangle_homography

    def reversed_corners(corners, size):
        return rectangle_homography(np.asarray(corners, dtype=float)[::-1], size)

    with pytest.raises(AssertionError, match="opposite senses"):
        check("rectangle_homography", reversed_corners)


def test_a_long_list_answer_is_summarised_as_an_array_would_be():
    """H11-13: an image returned with .tolist() once printed about 2 KB of floats."""
    from camlab import sensor

    with pytest.raises(AssertionError) as info:
        check("demosaic_bilinear", lambda raw, p: sensor.demosaic_bilinear(raw, p).tolist())
    assert "<list of shape (6, 6, 3), values" in str(info.value) and len(str(info.value)) < 800


def test_alias_frequency_checks_the_prompt_s_array_on_2d_and_0d_inputs():
    from camlab.exercises._core import CheckFailed

    right = lambda f: np.minimum(np.asarray(f) % 1, 1 - np.asarray(f) % 1)  # noqa: E731
    assert check("alias_frequency", right).passed is True  # a 0-d f gives one number back
    with pytest.raises(CheckFailed, match="wrap the values in np.array"):
        check("alias_frequency", lambda f: right(f).tolist())
    with pytest.raises(CheckFailed, match="f's shape"):
        check("alias_frequency", lambda f: np.array([right(x) for x in np.ravel(f)]))
    with pytest.raises(CheckFailed, match="your answer is integer"):
        check("alias_frequency", lambda f: right(f).astype(int))
