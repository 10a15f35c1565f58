from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.quaternion_sample import QuaternionSample





T = TypeVar("T", bound="AttitudeSpec")



@_attrs_define
class AttitudeSpec:
    """ An attitude law: body → TEME at each epoch. `law` and its parameters:
    - `nadir`: body +z at the geocentre, +y along −(r×v), +x completing the set (along
      the velocity on a circular orbit); optional `yaw_deg` about +z (default 0).
    - `sun-pointing`: the body `axis` (default [0, 0, 1]) at the Sun, the body
      `secondary` axis (default [1, 0, 0]; its part perpendicular to `axis`) towards the
      TEME pole projected across the Sun's direction.
    - `inertial`: a fixed `quaternion` [w, x, y, z] body → TEME.
    - `spin`: about the TEME `axis` at `rate_deg_s`, `phase_deg` at `times.start`
      (default 0), after the optional `quaternion` (default identity).
    - `quaternions`: a `series` of `{ "t": ..., "q": [w, x, y, z] }` (t in ISO UTC or
      seconds after `times.start`, increasing), SLERP between them; every epoch must lie
      within the series.
    - `tumble`: a torque-free rigid body: `inertia_kg_m2` (principal moments
      [I_x, I_y, I_z] along the body axes, or a symmetric 3×3 tensor), `omega_deg_s`
      (body-frame angular velocity at `times.start`) and `quaternion` (body → TEME
      then, default identity). Closed form when two principal moments are equal;
      otherwise a 6th-order splitting integrator.
    - `aem`: a CCSDS Attitude Ephemeris Message as KVN `text` (v1 with `QUATERNION_TYPE`
      FIRST or LAST, or v2, scalar last), quaternion data in TEME (`REF_FRAME_A`/`B`: TEME
      and `SC_BODY_n`, either way round, `ATTITUDE_DIR` A2B or B2A; A2B turns frame A's
      axes onto frame B's), SLERP between lines; the data must cover the window.

        Attributes:
            law (str):  Example: nadir.
            yaw_deg (float | None | Unset):
            quaternion (list[float] | None | Unset):
            axis (list[float] | None | Unset):
            rate_deg_s (float | None | Unset):
            phase_deg (float | None | Unset):
            series (list[QuaternionSample] | None | Unset):
            inertia_kg_m2 (list[float] | list[list[float]] | None | Unset):
            omega_deg_s (list[float] | None | Unset):
            secondary (list[float] | None | Unset): Law `sun-pointing`: the body axis kept towards the TEME pole (default
                [1, 0, 0]).
            text (None | str | Unset): Law `aem`: the CCSDS AEM, KVN text.
     """

    law: str
    yaw_deg: float | None | Unset = UNSET
    quaternion: list[float] | None | Unset = UNSET
    axis: list[float] | None | Unset = UNSET
    rate_deg_s: float | None | Unset = UNSET
    phase_deg: float | None | Unset = UNSET
    series: list[QuaternionSample] | None | Unset = UNSET
    inertia_kg_m2: list[float] | list[list[float]] | None | Unset = UNSET
    omega_deg_s: list[float] | None | Unset = UNSET
    secondary: list[float] | None | Unset = UNSET
    text: None | str | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.quaternion_sample import QuaternionSample # noqa: PLC0415
        law = self.law

        yaw_deg: float | None | Unset
        if isinstance(self.yaw_deg, Unset):
            yaw_deg = UNSET
        else:
            yaw_deg = self.yaw_deg

        quaternion: list[float] | None | Unset
        if isinstance(self.quaternion, Unset):
            quaternion = UNSET
        elif isinstance(self.quaternion, list):
            quaternion = self.quaternion


        else:
            quaternion = self.quaternion

        axis: list[float] | None | Unset
        if isinstance(self.axis, Unset):
            axis = UNSET
        elif isinstance(self.axis, list):
            axis = self.axis


        else:
            axis = self.axis

        rate_deg_s: float | None | Unset
        if isinstance(self.rate_deg_s, Unset):
            rate_deg_s = UNSET
        else:
            rate_deg_s = self.rate_deg_s

        phase_deg: float | None | Unset
        if isinstance(self.phase_deg, Unset):
            phase_deg = UNSET
        else:
            phase_deg = self.phase_deg

        series: list[dict[str, Any]] | None | Unset
        if isinstance(self.series, Unset):
            series = UNSET
        elif isinstance(self.series, list):
            series = []
            for series_type_0_item_data in self.series:
                series_type_0_item = series_type_0_item_data.to_dict()
                series.append(series_type_0_item)


        else:
            series = self.series

        inertia_kg_m2: list[float] | list[list[float]] | None | Unset
        if isinstance(self.inertia_kg_m2, Unset):
            inertia_kg_m2 = UNSET
        elif isinstance(self.inertia_kg_m2, list):
            inertia_kg_m2 = self.inertia_kg_m2


        elif isinstance(self.inertia_kg_m2, list):
            inertia_kg_m2 = []
            for componentsschemas_inertia_spec_type_1_item_data in self.inertia_kg_m2:
                componentsschemas_inertia_spec_type_1_item = componentsschemas_inertia_spec_type_1_item_data


                inertia_kg_m2.append(componentsschemas_inertia_spec_type_1_item)


        else:
            inertia_kg_m2 = self.inertia_kg_m2

        omega_deg_s: list[float] | None | Unset
        if isinstance(self.omega_deg_s, Unset):
            omega_deg_s = UNSET
        elif isinstance(self.omega_deg_s, list):
            omega_deg_s = self.omega_deg_s


        else:
            omega_deg_s = self.omega_deg_s

        secondary: list[float] | None | Unset
        if isinstance(self.secondary, Unset):
            secondary = UNSET
        elif isinstance(self.secondary, list):
            secondary = self.secondary


        else:
            secondary = self.secondary

        text: None | str | Unset
        if isinstance(self.text, Unset):
            text = UNSET
        else:
            text = self.text


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "law": law,
        })
        if yaw_deg is not UNSET:
            field_dict["yaw_deg"] = yaw_deg
        if quaternion is not UNSET:
            field_dict["quaternion"] = quaternion
        if axis is not UNSET:
            field_dict["axis"] = axis
        if rate_deg_s is not UNSET:
            field_dict["rate_deg_s"] = rate_deg_s
        if phase_deg is not UNSET:
            field_dict["phase_deg"] = phase_deg
        if series is not UNSET:
            field_dict["series"] = series
        if inertia_kg_m2 is not UNSET:
            field_dict["inertia_kg_m2"] = inertia_kg_m2
        if omega_deg_s is not UNSET:
            field_dict["omega_deg_s"] = omega_deg_s
        if secondary is not UNSET:
            field_dict["secondary"] = secondary
        if text is not UNSET:
            field_dict["text"] = text

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.quaternion_sample import QuaternionSample # noqa: PLC0415
        d = dict(src_dict)
        law = d.pop("law")

        def _parse_yaw_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        yaw_deg = _parse_yaw_deg(d.pop("yaw_deg", UNSET))


        def _parse_quaternion(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                quaternion_type_0 = cast(list[float], data)

                return quaternion_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        quaternion = _parse_quaternion(d.pop("quaternion", UNSET))


        def _parse_axis(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                axis_type_0 = cast(list[float], data)

                return axis_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        axis = _parse_axis(d.pop("axis", UNSET))


        def _parse_rate_deg_s(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        rate_deg_s = _parse_rate_deg_s(d.pop("rate_deg_s", UNSET))


        def _parse_phase_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        phase_deg = _parse_phase_deg(d.pop("phase_deg", UNSET))


        def _parse_series(data: object) -> list[QuaternionSample] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                series_type_0 = []
                _series_type_0 = data
                for series_type_0_item_data in (_series_type_0):
                    series_type_0_item = QuaternionSample.from_dict(series_type_0_item_data)



                    series_type_0.append(series_type_0_item)

                return series_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[QuaternionSample] | None | Unset, data)

        series = _parse_series(d.pop("series", UNSET))


        def _parse_inertia_kg_m2(data: object) -> list[float] | list[list[float]] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                componentsschemas_inertia_spec_type_0 = cast(list[float], data)

                return componentsschemas_inertia_spec_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            try:
                if not isinstance(data, list):
                    raise TypeError()
                componentsschemas_inertia_spec_type_1 = []
                _componentsschemas_inertia_spec_type_1 = data
                for componentsschemas_inertia_spec_type_1_item_data in (_componentsschemas_inertia_spec_type_1):
                    componentsschemas_inertia_spec_type_1_item = cast(list[float], componentsschemas_inertia_spec_type_1_item_data)

                    componentsschemas_inertia_spec_type_1.append(componentsschemas_inertia_spec_type_1_item)

                return componentsschemas_inertia_spec_type_1
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | list[list[float]] | None | Unset, data)

        inertia_kg_m2 = _parse_inertia_kg_m2(d.pop("inertia_kg_m2", UNSET))


        def _parse_omega_deg_s(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                omega_deg_s_type_0 = cast(list[float], data)

                return omega_deg_s_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        omega_deg_s = _parse_omega_deg_s(d.pop("omega_deg_s", UNSET))


        def _parse_secondary(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                secondary_type_0 = cast(list[float], data)

                return secondary_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        secondary = _parse_secondary(d.pop("secondary", UNSET))


        def _parse_text(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        text = _parse_text(d.pop("text", UNSET))


        attitude_spec = cls(
            law=law,
            yaw_deg=yaw_deg,
            quaternion=quaternion,
            axis=axis,
            rate_deg_s=rate_deg_s,
            phase_deg=phase_deg,
            series=series,
            inertia_kg_m2=inertia_kg_m2,
            omega_deg_s=omega_deg_s,
            secondary=secondary,
            text=text,
        )

        return attitude_spec

