from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="SiteSpec")



@_attrs_define
class SiteSpec:
    """ A ground site on the WGS-84 ellipsoid.

        Attributes:
            lat_deg (float): Geodetic latitude, degrees (−90 to 90). Example: 32.78.
            lon_deg (float): Longitude, degrees east (−180 to 360). Example: -105.82.
            alt_m (float | None | Unset): Height above the ellipsoid, m (−500 to 100 000). Default 0. Example: 2790.0.
     """

    lat_deg: float
    lon_deg: float
    alt_m: float | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        lat_deg = self.lat_deg

        lon_deg = self.lon_deg

        alt_m: float | None | Unset
        if isinstance(self.alt_m, Unset):
            alt_m = UNSET
        else:
            alt_m = self.alt_m


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "lat_deg": lat_deg,
            "lon_deg": lon_deg,
        })
        if alt_m is not UNSET:
            field_dict["alt_m"] = alt_m

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        lat_deg = d.pop("lat_deg")

        lon_deg = d.pop("lon_deg")

        def _parse_alt_m(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        alt_m = _parse_alt_m(d.pop("alt_m", UNSET))


        site_spec = cls(
            lat_deg=lat_deg,
            lon_deg=lon_deg,
            alt_m=alt_m,
        )

        return site_spec

