from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast






T = TypeVar("T", bound="SolverReport")



@_attrs_define
class SolverReport:
    """ What a fit reports about how its solver went.

        Attributes:
            algorithm (str): `levenberg-marquardt` (the crate; MINPACK's lmder).
            loss (str): Loss: `l2`, `huber` or `cauchy` (IRLS).
            starts (int): Starts tried; the reported fit is the best of them.
            start_rms (list[float]): RMS of the fit-space residuals each start ended with (in start order): more than
                one distinct value means several minima.
            evaluations (int): Model evaluations over all starts, Jacobians included.
            converged (bool): Whether the best start's last solve met its tolerances.
            termination (str): The solver's own termination reason for the best start.
            wall_time_s (float): Wall time of the whole fit, s.
     """

    algorithm: str
    loss: str
    starts: int
    start_rms: list[float]
    evaluations: int
    converged: bool
    termination: str
    wall_time_s: float
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        algorithm = self.algorithm

        loss = self.loss

        starts = self.starts

        start_rms = self.start_rms



        evaluations = self.evaluations

        converged = self.converged

        termination = self.termination

        wall_time_s = self.wall_time_s


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "algorithm": algorithm,
            "loss": loss,
            "starts": starts,
            "start_rms": start_rms,
            "evaluations": evaluations,
            "converged": converged,
            "termination": termination,
            "wall_time_s": wall_time_s,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        algorithm = d.pop("algorithm")

        loss = d.pop("loss")

        starts = d.pop("starts")

        start_rms = cast(list[float], d.pop("start_rms"))


        evaluations = d.pop("evaluations")

        converged = d.pop("converged")

        termination = d.pop("termination")

        wall_time_s = d.pop("wall_time_s")

        solver_report = cls(
            algorithm=algorithm,
            loss=loss,
            starts=starts,
            start_rms=start_rms,
            evaluations=evaluations,
            converged=converged,
            termination=termination,
            wall_time_s=wall_time_s,
        )


        solver_report.additional_properties = d
        return solver_report

    @property
    def additional_keys(self) -> list[str]:
        return list(self.additional_properties.keys())

    def __getitem__(self, key: str) -> Any:
        return self.additional_properties[key]

    def __setitem__(self, key: str, value: Any) -> None:
        self.additional_properties[key] = value

    def __delitem__(self, key: str) -> None:
        del self.additional_properties[key]

    def __contains__(self, key: str) -> bool:
        return key in self.additional_properties
