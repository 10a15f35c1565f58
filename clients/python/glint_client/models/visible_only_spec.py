from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="VisibleOnlySpec")



@_attrs_define
class VisibleOnlySpec:
    """ Which epochs a site can observe.

        Attributes:
            min_elevation_deg (float | None | Unset): Least elevation of the object, degrees (−90 to 90). Default 10.
            max_sun_elevation_deg (float | None | Unset): Greatest elevation of the Sun at the site, degrees (−90 to 90).
                Default −6
                (the end of civil twilight).
     """

    min_elevation_deg: float | None | Unset = UNSET
    max_sun_elevation_deg: float | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        min_elevation_deg: float | None | Unset
        if isinstance(self.min_elevation_deg, Unset):
            min_elevation_deg = UNSET
        else:
            min_elevation_deg = self.min_elevation_deg

        max_sun_elevation_deg: float | None | Unset
        if isinstance(self.max_sun_elevation_deg, Unset):
            max_sun_elevation_deg = UNSET
        else:
            max_sun_elevation_deg = self.max_sun_elevation_deg


        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if min_elevation_deg is not UNSET:
            field_dict["min_elevation_deg"] = min_elevation_deg
        if max_sun_elevation_deg is not UNSET:
            field_dict["max_sun_elevation_deg"] = max_sun_elevation_deg

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        def _parse_min_elevation_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        min_elevation_deg = _parse_min_elevation_deg(d.pop("min_elevation_deg", UNSET))


        def _parse_max_sun_elevation_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        max_sun_elevation_deg = _parse_max_sun_elevation_deg(d.pop("max_sun_elevation_deg", UNSET))


        visible_only_spec = cls(
            min_elevation_deg=min_elevation_deg,
            max_sun_elevation_deg=max_sun_elevation_deg,
        )

        return visible_only_spec

