from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="EpochSpec")



@_attrs_define
class EpochSpec:
    """ One epoch's geometry, in the body frame (or inertial when `attitude` is given).

        Attributes:
            t (float): Seconds, or an ISO 8601 UTC time string (reported as Unix seconds). Example: 0.0.
            sun (list[float]): Direction from the object to the Sun (any length; normalised).
            observer (list[float]): Vector from the object to the observer, metres; its length is the range R. It must
                lie outside the mesh's bounding sphere (Eq. 12 is a far-field sum).
            earth (list[float] | None | Unset): Vector from the object to the Earth's centre, metres. Needed for earthshine
                and eclipses.
            sun_distance_au (float | None | Unset): Object–Sun distance in AU. Default 1.
            attitude (list[float] | None | Unset): Body-to-inertial attitude quaternion [w, x, y, z]; when given, `sun`,
                `observer`
                and `earth` are inertial and are rotated into the body frame.
     """

    t: float
    sun: list[float]
    observer: list[float]
    earth: list[float] | None | Unset = UNSET
    sun_distance_au: float | None | Unset = UNSET
    attitude: list[float] | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        t = self.t

        sun = self.sun



        observer = self.observer



        earth: list[float] | None | Unset
        if isinstance(self.earth, Unset):
            earth = UNSET
        elif isinstance(self.earth, list):
            earth = self.earth


        else:
            earth = self.earth

        sun_distance_au: float | None | Unset
        if isinstance(self.sun_distance_au, Unset):
            sun_distance_au = UNSET
        else:
            sun_distance_au = self.sun_distance_au

        attitude: list[float] | None | Unset
        if isinstance(self.attitude, Unset):
            attitude = UNSET
        elif isinstance(self.attitude, list):
            attitude = self.attitude


        else:
            attitude = self.attitude


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "t": t,
            "sun": sun,
            "observer": observer,
        })
        if earth is not UNSET:
            field_dict["earth"] = earth
        if sun_distance_au is not UNSET:
            field_dict["sun_distance_au"] = sun_distance_au
        if attitude is not UNSET:
            field_dict["attitude"] = attitude

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        t = d.pop("t")

        sun = cast(list[float], d.pop("sun"))


        observer = cast(list[float], d.pop("observer"))


        def _parse_earth(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                earth_type_0 = cast(list[float], data)

                return earth_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        earth = _parse_earth(d.pop("earth", UNSET))


        def _parse_sun_distance_au(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        sun_distance_au = _parse_sun_distance_au(d.pop("sun_distance_au", UNSET))


        def _parse_attitude(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                attitude_type_0 = cast(list[float], data)

                return attitude_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        attitude = _parse_attitude(d.pop("attitude", UNSET))


        epoch_spec = cls(
            t=t,
            sun=sun,
            observer=observer,
            earth=earth,
            sun_distance_au=sun_distance_au,
            attitude=attitude,
        )

        return epoch_spec

