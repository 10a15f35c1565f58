from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.articulation_spec import ArticulationSpec
  from ..models.attitude_spec import AttitudeSpec
  from ..models.earth_orientation_spec import EarthOrientationSpec
  from ..models.orbit_spec import OrbitSpec
  from ..models.site_spec import SiteSpec
  from ..models.times_spec import TimesSpec
  from ..models.visible_only_spec import VisibleOnlySpec





T = TypeVar("T", bound="GeometrySpec")



@_attrs_define
class GeometrySpec:
    """ Epochs from an orbit, a site and a window: for each time, SGP4 gives the object's
    TEME state, Meeus' low-accuracy series (0.01°) the Sun, and the attitude law the body
    frame; the engine then sees the Sun, the site and the Earth's centre in the body
    frame as with explicit epochs. Positions are geometric (no refraction, no light
    time). The inertial frame of attitudes is TEME (true equator, mean equinox of date).

        Attributes:
            orbit (OrbitSpec): The orbit: a TLE (2 lines, or 3 with the name first), a CCSDS OMM in its JSON form, or
                a CCSDS OEM ephemeris. Exactly one. Propagated by SGP4 (AFSPC-compatible mode, WGS-72); times must lie
                within 30 days of the element set's epoch.
            site (SiteSpec): A ground site on the WGS-84 ellipsoid.
            times (TimesSpec): The window: epochs at `start`, `start + step_s`, … up to `stop` inclusive.
            attitude (AttitudeSpec): An attitude law: body → TEME at each epoch. `law` and its parameters:
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
            earth_orientation (EarthOrientationSpec | None | Unset):
            visible_only (None | Unset | VisibleOnlySpec):
            articulation (list[ArticulationSpec] | None | Unset): Parts of the mesh that turn about hinges each epoch (solar
                arrays). Absent: the
                mesh is rigid.
     """

    orbit: OrbitSpec
    site: SiteSpec
    times: TimesSpec
    attitude: AttitudeSpec
    earth_orientation: EarthOrientationSpec | None | Unset = UNSET
    visible_only: None | Unset | VisibleOnlySpec = UNSET
    articulation: list[ArticulationSpec] | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.articulation_spec import ArticulationSpec # noqa: PLC0415
        from ..models.attitude_spec import AttitudeSpec # noqa: PLC0415
        from ..models.earth_orientation_spec import EarthOrientationSpec # noqa: PLC0415
        from ..models.orbit_spec import OrbitSpec # noqa: PLC0415
        from ..models.site_spec import SiteSpec # noqa: PLC0415
        from ..models.times_spec import TimesSpec # noqa: PLC0415
        from ..models.visible_only_spec import VisibleOnlySpec # noqa: PLC0415
        orbit = self.orbit.to_dict()

        site = self.site.to_dict()

        times = self.times.to_dict()

        attitude = self.attitude.to_dict()

        earth_orientation: dict[str, Any] | None | Unset
        if isinstance(self.earth_orientation, Unset):
            earth_orientation = UNSET
        elif isinstance(self.earth_orientation, EarthOrientationSpec):
            earth_orientation = self.earth_orientation.to_dict()
        else:
            earth_orientation = self.earth_orientation

        visible_only: dict[str, Any] | None | Unset
        if isinstance(self.visible_only, Unset):
            visible_only = UNSET
        elif isinstance(self.visible_only, VisibleOnlySpec):
            visible_only = self.visible_only.to_dict()
        else:
            visible_only = self.visible_only

        articulation: list[dict[str, Any]] | None | Unset
        if isinstance(self.articulation, Unset):
            articulation = UNSET
        elif isinstance(self.articulation, list):
            articulation = []
            for articulation_type_0_item_data in self.articulation:
                articulation_type_0_item = articulation_type_0_item_data.to_dict()
                articulation.append(articulation_type_0_item)


        else:
            articulation = self.articulation


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "orbit": orbit,
            "site": site,
            "times": times,
            "attitude": attitude,
        })
        if earth_orientation is not UNSET:
            field_dict["earth_orientation"] = earth_orientation
        if visible_only is not UNSET:
            field_dict["visible_only"] = visible_only
        if articulation is not UNSET:
            field_dict["articulation"] = articulation

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.articulation_spec import ArticulationSpec # noqa: PLC0415
        from ..models.attitude_spec import AttitudeSpec # noqa: PLC0415
        from ..models.earth_orientation_spec import EarthOrientationSpec # noqa: PLC0415
        from ..models.orbit_spec import OrbitSpec # noqa: PLC0415
        from ..models.site_spec import SiteSpec # noqa: PLC0415
        from ..models.times_spec import TimesSpec # noqa: PLC0415
        from ..models.visible_only_spec import VisibleOnlySpec # noqa: PLC0415
        d = dict(src_dict)
        orbit = OrbitSpec.from_dict(d.pop("orbit"))




        site = SiteSpec.from_dict(d.pop("site"))




        times = TimesSpec.from_dict(d.pop("times"))




        attitude = AttitudeSpec.from_dict(d.pop("attitude"))




        def _parse_earth_orientation(data: object) -> EarthOrientationSpec | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                earth_orientation_type_0 = EarthOrientationSpec.from_dict(data)



                return earth_orientation_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(EarthOrientationSpec | None | Unset, data)

        earth_orientation = _parse_earth_orientation(d.pop("earth_orientation", UNSET))


        def _parse_visible_only(data: object) -> None | Unset | VisibleOnlySpec:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                visible_only_type_0 = VisibleOnlySpec.from_dict(data)



                return visible_only_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | Unset | VisibleOnlySpec, data)

        visible_only = _parse_visible_only(d.pop("visible_only", UNSET))


        def _parse_articulation(data: object) -> list[ArticulationSpec] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                articulation_type_0 = []
                _articulation_type_0 = data
                for articulation_type_0_item_data in (_articulation_type_0):
                    articulation_type_0_item = ArticulationSpec.from_dict(articulation_type_0_item_data)



                    articulation_type_0.append(articulation_type_0_item)

                return articulation_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[ArticulationSpec] | None | Unset, data)

        articulation = _parse_articulation(d.pop("articulation", UNSET))


        geometry_spec = cls(
            orbit=orbit,
            site=site,
            times=times,
            attitude=attitude,
            earth_orientation=earth_orientation,
            visible_only=visible_only,
            articulation=articulation,
        )

        return geometry_spec

