"""Lesson 04's normalisation study: the raw DLT, its conditioning, the predicted error, the survey."""

import numpy as np
import pytest

from camlab import CamlabInputError, fixtures
from camlab import camera as cm
from camlab.exercises.projective_camera._dlt_survey import _noisy_survey


def test_dlt_matrix_annihilates_the_true_camera():
    cam, X, _ = fixtures.resection_set(8, 0.0)
    A = cm.dlt_matrix(X, cam.project(X))
    assert A.shape == (16, 12)
    assert np.abs(A @ cam.P.ravel()).max() < 1e-9 * np.abs(A).max()


def test_unnormalised_dlt_exact_but_moved_by_the_origin_with_noise():
    cam, X, uv = fixtures.resection_set(8, 0.0)
    P = cm.unnormalised_dlt(X, uv)
    assert np.allclose(cm.project_points(P, X), uv, atol=1e-6)
    _, X, uv = fixtures.resection_set(30, 1.0)
    fx = [
        cm.decompose_projection_matrix(cm.unnormalised_dlt(X + s, uv)).K[0, 0]
        for s in (0.0, [100.0, 100.0, 0.0])
    ]
    assert abs(fx[1] - fx[0]) > 0.5  # the plain DLT depends on the origin


def test_conditioning_drops_with_normalisation():
    _, X, uv = fixtures.resection_set(30, 1.0)
    c = cm.dlt_conditioning(X, uv)
    assert c["pixels and metres"] > 1000 and c["normalised"] < 10


def test_predicted_rms_error_matches_monte_carlo():
    survey = fixtures.dlt_survey()
    predicted = cm.predicted_rms_error(
        survey.camera.P, survey.points_world, 1.0, survey.points_fresh
    )
    draws = fixtures.survey_draws(60)
    assert abs(draws["normalised"].rms_fresh - predicted) < 0.15 * predicted
    assert draws["plain DLT"].rms_fresh > 1.5 * predicted


def test_survey_is_exercise_4s():
    survey, (X, uv) = fixtures.dlt_survey(), _noisy_survey()
    assert np.array_equal(survey.points_world, X) and np.allclose(
        survey.points_image, uv, atol=1e-9
    )


def test_bad_input_named():
    with pytest.raises(CamlabInputError, match="points_world"):
        cm.dlt_matrix(np.zeros((5, 3)), np.zeros((5, 2)))
    with pytest.raises(CamlabInputError, match="sigma"):
        survey = fixtures.dlt_survey()
        cm.predicted_rms_error(survey.camera.P, survey.points_world, -1.0, survey.points_fresh)
