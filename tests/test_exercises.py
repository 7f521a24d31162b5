"""Every registered exercise: the reference passes, a stub is 'not attempted', mistakes are diagnosed."""
import pytest

from camlab import exercises
from camlab.exercises import all_exercises, check, solution

EXERCISES = all_exercises()


def _stub(*args):
    raise NotImplementedError


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_reference_passes(name, capsys):
    assert check(name, EXERCISES[name].reference) is True
    assert "correct on all" in capsys.readouterr().out


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_stub_reports_not_attempted(name, capsys):
    assert check(name, _stub) is False
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


@pytest.mark.parametrize("name", sorted(EXERCISES))
def test_solution_prints_the_library_source(name, capsys):
    source = solution(name)
    assert f"def {EXERCISES[name].reference.__name__}(" in source
    assert source in capsys.readouterr().out


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
