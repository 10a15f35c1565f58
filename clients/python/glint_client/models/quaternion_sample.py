from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast






T = TypeVar("T", bound="QuaternionSample")



@_attrs_define
class QuaternionSample:
    """ One sample of an attitude series.

        Attributes:
            t (float): ISO 8601 UTC, or seconds after `times.start`. Example: 0.0.
            q (list[float]): Body → TEME, [w, x, y, z], unit.
     """

    t: float
    q: list[float]





    def to_dict(self) -> dict[str, Any]:
        t = self.t

        q = self.q




        field_dict: dict[str, Any] = {}

        field_dict.update({
            "t": t,
            "q": q,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        t = d.pop("t")

        q = cast(list[float], d.pop("q"))


        quaternion_sample = cls(
            t=t,
            q=q,
        )

        return quaternion_sample

