from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="Observation")



@_attrs_define
class Observation:
    """ One observation of the object's apparent magnitude.

        Attributes:
            t (float): Time, seconds: the `t` of one of the request's epochs (Unix seconds for ISO times).
            magnitude (float): Apparent magnitude (the band of the request's illumination).
            sigma (float): 1σ error of the magnitude (> 0).
     """

    t: float
    magnitude: float
    sigma: float





    def to_dict(self) -> dict[str, Any]:
        t = self.t

        magnitude = self.magnitude

        sigma = self.sigma


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "t": t,
            "magnitude": magnitude,
            "sigma": sigma,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        t = d.pop("t")

        magnitude = d.pop("magnitude")

        sigma = d.pop("sigma")

        observation = cls(
            t=t,
            magnitude=magnitude,
            sigma=sigma,
        )

        return observation

