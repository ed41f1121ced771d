"""Scenarios of one's own for the studies' tests (``kind = "custom"``, ``tests/test_vehicle_study.py``):
importable as ``study_scenarios`` (pytest puts ``tests/`` on ``sys.path``; a Ray worker gets it
through ``PYTHONPATH``)."""

import math
import os
import sys


def oscillator(parameters: dict) -> dict:
    """A damped oscillator let go from 1: its amplitude after ``time`` and the parameters seen."""
    omega = math.sqrt(parameters["stiffness"] / parameters["mass"])
    amplitude = math.exp(-parameters["damping"] * parameters["time"]) * abs(math.cos(omega * parameters["time"]))
    return {"amplitude": amplitude, "seen": float(len(parameters)), "label_length": float(len(parameters["label"]))}


def where_am_i(parameters: dict) -> dict:
    """The process that ran it (on Ray: a worker, not the driver)."""
    return {"pid": float(os.getpid())}


def not_metrics(parameters: dict) -> str:
    return "metrics"


def not_finite(parameters: dict) -> dict:
    return {"amplitude": math.nan, "seen": 1.0, "label_length": 1.0}


def a_flag(parameters: dict) -> dict:
    return {"amplitude": True, "seen": 1.0, "label_length": 1.0}


def one_too_many(parameters: dict) -> dict:
    return {"amplitude": 1.0, "seen": 1.0, "label_length": 1.0, "extra": 2.0}


def exits(parameters: dict) -> dict:
    sys.exit(3)


def two_arguments(parameters: dict, other: dict) -> dict:
    return {}


class NotAFunction:
    def __init__(self, parameters: dict) -> None:
        self.parameters = parameters
