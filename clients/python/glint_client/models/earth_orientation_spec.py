from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="EarthOrientationSpec")



@_attrs_define
class EarthOrientationSpec:
    """ Earth orientation parameters (IERS Bulletin A values for the day).

        Attributes:
            dut1_s (float | None | Unset): UT1 − UTC, s (−1 to 1). Default 0.
            xp_arcsec (float | None | Unset): Pole offset x_p, arcsec (−2 to 2). Default 0.
            yp_arcsec (float | None | Unset): Pole offset y_p, arcsec (−2 to 2). Default 0.
     """

    dut1_s: float | None | Unset = UNSET
    xp_arcsec: float | None | Unset = UNSET
    yp_arcsec: float | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        dut1_s: float | None | Unset
        if isinstance(self.dut1_s, Unset):
            dut1_s = UNSET
        else:
            dut1_s = self.dut1_s

        xp_arcsec: float | None | Unset
        if isinstance(self.xp_arcsec, Unset):
            xp_arcsec = UNSET
        else:
            xp_arcsec = self.xp_arcsec

        yp_arcsec: float | None | Unset
        if isinstance(self.yp_arcsec, Unset):
            yp_arcsec = UNSET
        else:
            yp_arcsec = self.yp_arcsec


        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if dut1_s is not UNSET:
            field_dict["dut1_s"] = dut1_s
        if xp_arcsec is not UNSET:
            field_dict["xp_arcsec"] = xp_arcsec
        if yp_arcsec is not UNSET:
            field_dict["yp_arcsec"] = yp_arcsec

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        def _parse_dut1_s(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        dut1_s = _parse_dut1_s(d.pop("dut1_s", UNSET))


        def _parse_xp_arcsec(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        xp_arcsec = _parse_xp_arcsec(d.pop("xp_arcsec", UNSET))


        def _parse_yp_arcsec(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        yp_arcsec = _parse_yp_arcsec(d.pop("yp_arcsec", UNSET))


        earth_orientation_spec = cls(
            dut1_s=dut1_s,
            xp_arcsec=xp_arcsec,
            yp_arcsec=yp_arcsec,
        )

        return earth_orientation_spec

