from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="AngleSample")



@_attrs_define
class AngleSample:
    """ One sample of a hinge angle.

        Attributes:
            t (float):  Example: 0.0.
            angle_deg (float):
     """

    t: float
    angle_deg: float





    def to_dict(self) -> dict[str, Any]:
        t = self.t

        angle_deg = self.angle_deg


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "t": t,
            "angle_deg": angle_deg,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        t = d.pop("t")

        angle_deg = d.pop("angle_deg")

        angle_sample = cls(
            t=t,
            angle_deg=angle_deg,
        )

        return angle_sample

