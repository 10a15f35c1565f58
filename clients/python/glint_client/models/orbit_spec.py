from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.orbit_spec_omm_type_0 import OrbitSpecOmmType0





T = TypeVar("T", bound="OrbitSpec")



@_attrs_define
class OrbitSpec:
    """ The orbit: a TLE (2 lines, or 3 with the name first), a CCSDS OMM in its JSON form, or
    a CCSDS OEM ephemeris. Exactly one. Propagated by SGP4 (AFSPC-compatible mode, WGS-72); times must lie
    within 30 days of the element set's epoch.

        Attributes:
            tle (list[str] | None | Unset): The lines of a two- or three-line element set (69 characters per data line,
                checksums validated).
            omm (None | OrbitSpecOmmType0 | Unset): A CCSDS OMM as JSON (CelesTrak's / Space-Track's keys: `EPOCH`,
                `MEAN_MOTION`, `ECCENTRICITY`, `INCLINATION`, `RA_OF_ASC_NODE`,
                `ARG_OF_PERICENTER`, `MEAN_ANOMALY`, `BSTAR`, `MEAN_MOTION_DOT`,
                `MEAN_MOTION_DDOT`, `NORAD_CAT_ID`, …). `EPOCH` is UTC without a zone suffix.
            oem (None | str | Unset): A CCSDS OEM (KVN text) instead of an element set, for precise orbits: states in
                TEME (EME2000/GCRF/ICRF are refused), interpolated by Lagrange polynomials of its
                `INTERPOLATION_DEGREE` (default 7); the window must lie within its states.
     """

    tle: list[str] | None | Unset = UNSET
    omm: None | OrbitSpecOmmType0 | Unset = UNSET
    oem: None | str | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.orbit_spec_omm_type_0 import OrbitSpecOmmType0 # noqa: PLC0415
        tle: list[str] | None | Unset
        if isinstance(self.tle, Unset):
            tle = UNSET
        elif isinstance(self.tle, list):
            tle = self.tle


        else:
            tle = self.tle

        omm: dict[str, Any] | None | Unset
        if isinstance(self.omm, Unset):
            omm = UNSET
        elif isinstance(self.omm, OrbitSpecOmmType0):
            omm = self.omm.to_dict()
        else:
            omm = self.omm

        oem: None | str | Unset
        if isinstance(self.oem, Unset):
            oem = UNSET
        else:
            oem = self.oem


        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if tle is not UNSET:
            field_dict["tle"] = tle
        if omm is not UNSET:
            field_dict["omm"] = omm
        if oem is not UNSET:
            field_dict["oem"] = oem

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.orbit_spec_omm_type_0 import OrbitSpecOmmType0 # noqa: PLC0415
        d = dict(src_dict)
        def _parse_tle(data: object) -> list[str] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                tle_type_0 = cast(list[str], data)

                return tle_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[str] | None | Unset, data)

        tle = _parse_tle(d.pop("tle", UNSET))


        def _parse_omm(data: object) -> None | OrbitSpecOmmType0 | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                omm_type_0 = OrbitSpecOmmType0.from_dict(data)



                return omm_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | OrbitSpecOmmType0 | Unset, data)

        omm = _parse_omm(d.pop("omm", UNSET))


        def _parse_oem(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        oem = _parse_oem(d.pop("oem", UNSET))


        orbit_spec = cls(
            tle=tle,
            omm=omm,
            oem=oem,
        )

        return orbit_spec

