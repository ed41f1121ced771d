"""Studies: one scenario simulated over grids and random draws of its parameters, each run a Ray
task (local by default, or a cluster), results written incrementally to Parquet
(``uwml study CONFIG.toml``; docs/scale.md).

* :mod:`uwml.study.config`: the TOML file (:func:`load`) and the runs it names;
* :mod:`uwml.study.scenarios`: what one run computes, its parameters and metrics; a floating
  vehicle of one's own holding station (:mod:`uwml.study.vehicle`), a function of one's own
  (:mod:`uwml.study.custom`);
* :mod:`uwml.study.runner`: running them (:func:`run_study`), resuming, failures;
* :mod:`uwml.study.store`: the output folder: its record, lock and parts, one row per run;
* :mod:`uwml.study.study_results`: reading them back (:func:`read_results`), summary, figures.
"""

from .config import ConfigError, StudyConfig, load, loads
from .runner import StudyOutcome, run_study
from .store import StudyError
from .study_results import figures, read_results, summary

__all__ = [
    "ConfigError",
    "StudyConfig",
    "StudyError",
    "StudyOutcome",
    "figures",
    "load",
    "loads",
    "read_results",
    "run_study",
    "summary",
]
