"""Every registered exercise: the reference passes, a stub is 'not attempted', mistakes are diagnosed."""
import builtins
import dis
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
TEACHING_LESSONS = {"00", "01", "02", "03", "04", "05", "06", "07", "08", "10", "11"}
TEACHING = sorted(n for n, e in EXERCISES.items() if e.teaching is not None)


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_solution_prints_the_teaching_solution_or_the_library_source(name, capsys):
    exercise = EXERCISES[name]
    assert solution(name) is None  # a bare call ending a cell shows the code once, not again as Out[]
    source = solution_source(name)
    shown = exercise.teaching or exercise.reference
    assert f"def {shown.__name__}(" in source
    assert capsys.readouterr().out == source + "\n"


@pytest.mark.parametrize("name", sorted(n for n, e in EXERCISES.items() if e.lesson in TEACHING_LESSONS))
def test_exercise_has_a_teaching_solution_named_like_it(name):
    teaching = EXERCISES[name].teaching
    assert teaching is not None, f"{name}: register a teaching solution (Exercise(..., teaching=fn))"
    assert teaching.__name__ == name, f"{name}: name the teaching solution like the student's function"


@pytest.mark.parametrize("name", TEACHING)
def test_teaching_solution_agrees_with_the_library(name, capsys):
    assert check(name, EXERCISES[name].teaching).passed is True
    assert "correct on all" in capsys.readouterr().out


def _globals_used(code: types.CodeType) -> set[str]:
    names = {i.argval for i in dis.get_instructions(code) if i.opname in ("LOAD_GLOBAL", "LOAD_NAME")}
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
        assert teaching.__globals__.get(used) is np, \
            f"{name}: the teaching solution uses {used!r}; it may use only numpy (np) and builtins"


def test_teaching_solution_check_catches_a_call_into_camlab():
    def leaky(x):
        return camlab_helper(x)  # noqa: F821
    assert "camlab_helper" in _globals_used(leaky.__code__)


def test_large_array_mismatch_is_summarised_not_printed():
    from camlab.exercises._core import _fmt, worst_mismatch
    expected = np.zeros((40, 50, 3))
    got = expected.copy()
    got[7, 9, 2] = 5.0
    assert _fmt(got).startswith("<array of shape (40, 50, 3)")
    line = worst_mismatch(got, expected)
    assert "(row, column, channel) (7, 9, 2): got 5, expected 0 (1 of 6000 entries differ by more than rtol 1e-05, atol 1e-08)" in line


def test_forgotten_return_is_named():
    with pytest.raises(AssertionError, match="forget `return`"):
        check("lift", lambda p: None)


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
        return f * np.ones((6, 2)) / np.ones(6)  # numpy's own error for (6, 2) / (6,), as X[:, :2] / X[:, 2] gives

    with pytest.raises(AssertionError, match=r"raised ValueError.*\n.*\n  likely cause: a broadcasting slip.*X\[:, 2:3\]"):
        check("pinhole_projection", project)


@pytest.mark.parametrize("divide", [lambda x: (x / x[:, 2])[:, :2], lambda x: x[:, :2] / x[:, 2]])
def test_project_points_divided_without_keepdims_gets_the_hint(divide):
    # lesson 04's exercise: the (N, 3) or (N, 2) block divided by the (N,) column x[:, 2]
    def project_points(P, X):
        return divide(np.c_[X, np.ones(len(X))] @ np.asarray(P).T)

    with pytest.raises(AssertionError, match=r"likely cause: a broadcasting slip.*keepdims=True"):
        check("project_points", project_points)


def test_pinhole_checks_pass_right_answers_in_other_forms(capsys):
    assert check("pinhole_projection", lambda X, f: f * np.asarray(X)[:, :2] / np.asarray(X)[:, [2]])
    assert check("pinhole_projection", lambda X, f: (f * np.asarray(X).T[:2] / np.asarray(X).T[2]).T)
    assert check("best_pinhole_diameter", lambda f, lam: (2.44 * lam * f) ** 0.5)


def test_best_pinhole_accepts_a_numerical_minimiser_and_rejects_a_few_percent_off(capsys):
    from scipy.optimize import minimize_scalar

    def bounded(f, lam):  # stops about 0.4 % from d*, where the blur is within 1e-5 of its least
        return minimize_scalar(lambda d: d + 2.44 * lam * f / d, bounds=(1e-6, 1e-2), method="bounded").x

    assert check("best_pinhole_diameter", bounded)
    with pytest.raises(AssertionError, match="minimise the total blur"):
        check("best_pinhole_diameter", lambda f, lam: 1.05 * (2.44 * lam * f) ** 0.5)


def test_a_function_that_changes_its_input_in_place_fails_naming_the_argument(capsys):
    def project_in_place(X, f):
        X[:, :2] *= f / X[:, 2:3]
        return X[:, :2]

    with pytest.raises(AssertionError, match=r"changed its input `X` in place(.|\n)*work on a copy"):
        check("pinhole_projection", project_in_place)


def test_counting_columns_from_one_is_named_as_such():
    for one_based in (lambda X, f: f * X[:, 1:3] / X[:, 3:4], lambda X, f: f * X[:, [1, 2]] / X[:, [3]]):
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
            result = shell.run_cell('from camlab.exercises import solution\nsolution("pinhole_projection")')
    finally:
        InteractiveShell.clear_instance()
    assert result.success and result.result is None
    assert shown.stdout.count("def pinhole_projection(") == 1 and "Out[" not in shown.stdout


def test_estimate_affine_camera_accepts_a_column_of_ones_instead_of_centring(capsys):
    from camlab.exercises.affine_cameras import _estimate_with_ones

    assert check("estimate_affine_camera", _estimate_with_ones).passed is True


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


def test_float32_answer_is_held_to_float32_precision_not_beyond():
    from camlab.exercises._core import Tolerance

    tol = Tolerance(rtol=1e-9, atol=0.0)
    expected = np.array([1.2, 2.4, 6.0])
    assert tol.for_answer(expected, expected) == tol                     # float64: the exercise's own
    widened = tol.for_answer(expected.astype(np.float32), expected)
    assert widened.rtol == pytest.approx(100 * np.finfo(np.float32).eps) and widened.atol == pytest.approx(6 * widened.rtol)
    with pytest.raises(AssertionError, match="wrong answer"):             # a real mistake in float32 still fails
        check("disparity_to_depth", lambda d, f, B: np.float32(1.001) * (f * B / d).astype(np.float32))


def test_mismatch_line_counts_with_the_exercises_tolerance_and_shows_the_digits():
    from camlab.exercises._core import Tolerance

    got, expected = np.array([1.2, 2.4 + 1e-12, 6.0]), np.array([1.2, 2.4, 6.0])
    line = worst_mismatch(got, expected, Tolerance(rtol=1e-14, atol=0.0))
    assert "got 2.400000000001, expected 2.4 (1 of 3 entries differ by more than rtol 1e-14, atol 0)" in line


def test_check_result_is_falsy_for_a_stub_and_prints_nothing_in_ipython(capsys):
    from IPython.core.interactiveshell import InteractiveShell

    result = check("lift", _stub)
    assert not result and repr(result) == "CheckResult('lift', passed=False)"
    assert check("lift", EXERCISES["lift"].reference)
    shell = InteractiveShell.instance()
    try:
        assert shell.display_formatter.format(result) == ({}, {})   # ends a cell: no stray `False`
    finally:
        InteractiveShell.clear_instance()


@pytest.fixture
def short_time_limit(monkeypatch):
    import signal
    import threading

    from camlab.exercises import _core

    if not hasattr(signal, "setitimer") or threading.current_thread() is not threading.main_thread():
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
    with pytest.raises(AssertionError, match=r"(?s)still running after 0.3 s on test input 1 of \d+.*input    \(\[\["):
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


def test_time_limit_restores_an_outer_timer():
    import signal

    from camlab.exercises._core import time_limit

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

    from camlab.exercises._core import time_limit

    seen = []

    def worker():
        with time_limit(0.01):
            seen.append(sum(range(10)))

    thread = threading.Thread(target=worker)
    thread.start()
    thread.join(5)
    assert seen == [45]


@pytest.mark.parametrize("name", sorted(EXERCISES))
@pytest.mark.parametrize("answer", ["oops", [np.zeros(2), 1.0], {"x": 1}], ids=["str", "ragged list", "dict"])
def test_an_answer_that_is_not_numbers_is_named_not_a_crash_inside_camlab(name, answer):
    with pytest.raises(AssertionError) as info:
        check(name, lambda *args: answer)
    message = str(info.value)
    assert "likely cause" in message, message
    expected = EXERCISES[name].reference(*EXERCISES[name].cases()[0])
    if isinstance(expected, (np.ndarray, float)):  # answers of other kinds (pairs of arrays) have their own hints
        assert f"you returned a {type(answer).__name__}" in message, message


def test_lift_rejects_a_list_since_its_prompt_asks_for_an_array_and_names_the_fix():
    with pytest.raises(AssertionError, match=r"wrong type of answer.*\n.*\n  got      \[2\.5, 4\.25, 1\.0\]  \(a list\)"
                                             r"(.|\n)*you returned a list; return a numpy array of shape \(3,\)"):
        check("lift", lambda p: [p[0], p[1], 1.0])


def test_ndarray_answer_is_not_demanded_where_the_prompt_does_not_ask(capsys):
    assert check("pinhole_projection", lambda X, f: (f * np.asarray(X)[:, :2] / np.asarray(X)[:, [2]]).tolist())


def test_a_ragged_np_array_inside_the_students_function_gets_a_hint():
    with pytest.raises(AssertionError, match=r"raised ValueError(.|\n)*likely cause: an array beside numbers.*np\.append"):
        check("lift", lambda p: np.array([p, 1]))


@pytest.mark.parametrize("right", [lambda p: np.r_[p, 1], lambda p: np.hstack([p, 1]), lambda p: np.concatenate((p, [1.0])),
                                   lambda p: np.array([p[0], p[1], 1]), lambda p: np.append(p, 1).astype(np.float32)],
                         ids=["r_", "hstack", "concatenate", "int literal", "float32"])
def test_lift_passes_right_answers_in_other_forms(right, capsys):
    assert check("lift", right).passed is True


def test_a_right_answer_that_changes_its_input_in_place_fails_naming_the_argument():
    """An in-place change of the caller's array (a typical mistake) fails, even when the answer is right."""
    from camlab import distortion

    def scaled_in_place(x, dist):
        out = distortion.distort_points(x, dist)
        x *= 1.0 + 0 * x  # a no-op in value: nothing changes, so this passes
        return out

    def overwritten(x, dist):
        x[:] = distortion.distort_points(x, dist)
        return x

    assert check("distort_points", scaled_in_place)
    with pytest.raises(AssertionError, match=r"changed its input `x` in place.*\n.*likely cause: an in-place operation"):
        check("distort_points", overwritten)


def _dlt_rms_normalised(X, uv):
    """The normalised DLT with H&Z's RMS distances (camlab uses mean distances), at another scale."""
    from camlab.exercises.projective_camera import _dlt_unnormalised

    X, uv = np.asarray(X, dtype=float), np.asarray(uv, dtype=float)

    def normaliser(p):
        c = p.mean(axis=0)
        s = np.sqrt(p.shape[1] / np.mean(np.sum((p - c) ** 2, axis=1)))
        return np.block([[s * np.eye(p.shape[1]), -s * c[:, None]], [np.zeros((1, p.shape[1])), 1.0]])

    U, T = normaliser(X), normaliser(uv)
    P_hat = _dlt_unnormalised((np.c_[X, np.ones(len(X))] @ U.T)[:, :3], (np.c_[uv, np.ones(len(uv))] @ T.T)[:, :2])
    return -42.0 * np.linalg.inv(T) @ P_hat @ U


def test_estimate_projection_matrix_accepts_rms_normalisation_at_another_scale(capsys):
    assert check("estimate_projection_matrix", _dlt_rms_normalised).passed is True


@pytest.mark.skipif(not hasattr(__import__("camlab.exercises._core").exercises._core, "_inputs_changed"),
                    reason="the shared in-place detector (_core._inputs_changed) arrives from another branch")
def test_in_place_division_of_P_in_project_points_gets_a_hint():
    def project_points(P, X):
        P /= P[2, 3]   # changes the caller's camera.P
        x = np.c_[X, np.ones(len(X))] @ P.T
        return x[:, :2] / x[:, 2:]

    with pytest.raises(AssertionError, match=r"in place"):
        check("project_points", project_points)
