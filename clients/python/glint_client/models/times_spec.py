from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="TimesSpec")



@_attrs_define
class TimesSpec:
    """ The window: epochs at `start`, `start + step_s`, … up to `stop` inclusive.

        Attributes:
            start (str): ISO 8601 UTC, e.g. `2026-12-03T01:00:00Z`. Example: 2026-12-03T01:00:00Z.
            stop (str): ISO 8601 UTC, not before `start`. Example: 2026-12-03T01:20:00Z.
            step_s (float): Seconds between epochs (≥ 0.001). Example: 1.0.
     """

    start: str
    stop: str
    step_s: float





    def to_dict(self) -> dict[str, Any]:
        start = self.start

        stop = self.stop

        step_s = self.step_s


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "start": start,
            "stop": stop,
            "step_s": step_s,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        start = d.pop("start")

        stop = d.pop("stop")

        step_s = d.pop("step_s")

        times_spec = cls(
            start=start,
            stop=stop,
            step_s=step_s,
        )

        return times_spec

