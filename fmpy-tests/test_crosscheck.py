"""FMI cross-check artefacts (`cargo xtask crosscheck`): they pass fmpy's
vendor-repository validation, and importing the FMU as the cross-check does
(fmpy, input file, options file) reproduces the reference results."""

import os

import numpy as np
import pytest

from conftest import TARGET

MODEL_DIR = TARGET / "cross-check" / "fmus" / "2.0" / "cs" / "linux64" / "RockingBlock"


@pytest.fixture(scope="module")
def model_dir():
    dirs = sorted(MODEL_DIR.glob("*/RockingBlock")) if MODEL_DIR.is_dir() else []
    if not dirs:
        pytest.skip(f"no cross-check artefacts under {MODEL_DIR}: run `cargo xtask crosscheck`")
    return str(dirs[-1])


def test_artefacts_pass_the_vendor_repository_validation(model_dir):
    from fmpy.cross_check.validate_vendor_repo import validate_test_fmu

    assert validate_test_fmu(model_dir) == []
    assert os.path.isfile(os.path.join(model_dir, "README.md"))


def test_import_reproduces_the_reference(model_dir):
    from fmpy import simulate_fmu
    from fmpy.util import read_csv, read_ref_opt_file

    name = os.path.join(model_dir, "RockingBlock")
    opt = read_ref_opt_file(name + "_ref.opt")
    ref = read_csv(name + "_ref.csv")
    result = simulate_fmu(
        name + ".fmu",
        start_time=opt["StartTime"],
        stop_time=opt["StopTime"],
        relative_tolerance=opt["RelTol"],
        output_interval=opt["StepSize"],
        input=read_csv(name + "_in.csv"),
        output=list(ref.dtype.names[1:]),
    )
    assert len(result) == len(ref)
    for n in ref.dtype.names:
        np.testing.assert_allclose(result[n].astype(float), ref[n], rtol=1e-12, atol=1e-12, err_msg=n)
    assert ref["impacts"][-1] > 0
