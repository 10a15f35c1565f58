from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.observation_result import ObservationResult





T = TypeVar("T", bound="EpochResult")



@_attrs_define
class EpochResult:
    """ Brightness of the object at one epoch.

        Attributes:
            t (float): Epoch time, seconds (Unix seconds when the request gave an ISO string).
            irradiance_w_m2 (float): Total irradiance at the observer, W/m² (band-integrated).
            sun_w_m2 (float): Part of the irradiance due to direct sunlight, W/m².
            earthshine_w_m2 (float): Part of the irradiance due to earthshine, W/m².
            intensity_w_sr (float): Radiant intensity of the object towards the observer, W/sr.
            phase_angle_deg (float): Sun–object–observer angle, degrees.
            range_m (float): Object–observer distance, m.
            lit_visible_area_m2 (float): Area both sunlit and seen by the observer, m².
            eclipse (float): Fraction of the solar disk hidden by the Earth (0 sunlit, 1 umbra).
            earth_blocks_view (bool): The Earth lies across the line of sight (the segment from the object to the
                observer passes through it): nothing reaches the observer, so the irradiances are 0
                and the magnitudes `null` (`intensity_w_sr` is still the object's). `false` when the
                epoch gives no `earth`.
            magnitude (float | None | Unset): Apparent magnitude in the request's band: m = m_sun − 2.5 log10(E / E_sun),
                E_sun
                the Sun's irradiance at 1 AU in the same band and m_sun its magnitude there (−26.74
                for a `band_um` interval; a named `band` carries its own). `null` when no light at
                all reaches the observer.
            magnitude_1000km (float | None | Unset): Range-normalised magnitude: `magnitude` moved to a range of 1000 km,
                m − 5 log10(R / 1000 km), the phase left as it is. `null` with `magnitude`.
                (Formerly `magnitude_std`.)
            magnitude_standard (float | None | Unset): The observers' standard magnitude: at 1000 km and 90° phase, the
                phase reduced with
                the Lambert sphere's phase law F(g) = ((π − g) cos g + sin g)/π:
                `magnitude_1000km` + 2.5 log10(F(g) / F(90°)). Constant over a light curve of a
                Lambertian sphere. `null` with `magnitude`, or at phase 180° (F = 0).
            magnitude_intrinsic (float | None | Unset): McCants' intrinsic magnitude: at 1000 km and full phase (0°), the
                phase reduced with
                the same Lambert sphere law: `magnitude_1000km` + 2.5 log10 F(g)
                (= `magnitude_standard` − 2.5 log10 π, 1.243 mag brighter). `null` with
                `magnitude_standard`.
            azimuth_deg (float | None | Unset): `geometry` requests only: the object's azimuth seen from the site, degrees
                from
                north through east (geometric, no refraction).
            elevation_deg (float | None | Unset): `geometry` requests only: the object's elevation above the site's horizon,
                degrees (geometric, no refraction).
            sun_elevation_deg (float | None | Unset): `geometry` requests only: the Sun's elevation at the site, degrees.
            in_earth_shadow (bool | None | Unset): `geometry` requests only: the Earth hides some of the Sun from the object
                (penumbra or umbra; `eclipse` says how much).
            observation (None | ObservationResult | Unset):
     """

    t: float
    irradiance_w_m2: float
    sun_w_m2: float
    earthshine_w_m2: float
    intensity_w_sr: float
    phase_angle_deg: float
    range_m: float
    lit_visible_area_m2: float
    eclipse: float
    earth_blocks_view: bool
    magnitude: float | None | Unset = UNSET
    magnitude_1000km: float | None | Unset = UNSET
    magnitude_standard: float | None | Unset = UNSET
    magnitude_intrinsic: float | None | Unset = UNSET
    azimuth_deg: float | None | Unset = UNSET
    elevation_deg: float | None | Unset = UNSET
    sun_elevation_deg: float | None | Unset = UNSET
    in_earth_shadow: bool | None | Unset = UNSET
    observation: None | ObservationResult | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.observation_result import ObservationResult # noqa: PLC0415
        t = self.t

        irradiance_w_m2 = self.irradiance_w_m2

        sun_w_m2 = self.sun_w_m2

        earthshine_w_m2 = self.earthshine_w_m2

        intensity_w_sr = self.intensity_w_sr

        phase_angle_deg = self.phase_angle_deg

        range_m = self.range_m

        lit_visible_area_m2 = self.lit_visible_area_m2

        eclipse = self.eclipse

        earth_blocks_view = self.earth_blocks_view

        magnitude: float | None | Unset
        if isinstance(self.magnitude, Unset):
            magnitude = UNSET
        else:
            magnitude = self.magnitude

        magnitude_1000km: float | None | Unset
        if isinstance(self.magnitude_1000km, Unset):
            magnitude_1000km = UNSET
        else:
            magnitude_1000km = self.magnitude_1000km

        magnitude_standard: float | None | Unset
        if isinstance(self.magnitude_standard, Unset):
            magnitude_standard = UNSET
        else:
            magnitude_standard = self.magnitude_standard

        magnitude_intrinsic: float | None | Unset
        if isinstance(self.magnitude_intrinsic, Unset):
            magnitude_intrinsic = UNSET
        else:
            magnitude_intrinsic = self.magnitude_intrinsic

        azimuth_deg: float | None | Unset
        if isinstance(self.azimuth_deg, Unset):
            azimuth_deg = UNSET
        else:
            azimuth_deg = self.azimuth_deg

        elevation_deg: float | None | Unset
        if isinstance(self.elevation_deg, Unset):
            elevation_deg = UNSET
        else:
            elevation_deg = self.elevation_deg

        sun_elevation_deg: float | None | Unset
        if isinstance(self.sun_elevation_deg, Unset):
            sun_elevation_deg = UNSET
        else:
            sun_elevation_deg = self.sun_elevation_deg

        in_earth_shadow: bool | None | Unset
        if isinstance(self.in_earth_shadow, Unset):
            in_earth_shadow = UNSET
        else:
            in_earth_shadow = self.in_earth_shadow

        observation: dict[str, Any] | None | Unset
        if isinstance(self.observation, Unset):
            observation = UNSET
        elif isinstance(self.observation, ObservationResult):
            observation = self.observation.to_dict()
        else:
            observation = self.observation


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "t": t,
            "irradiance_w_m2": irradiance_w_m2,
            "sun_w_m2": sun_w_m2,
            "earthshine_w_m2": earthshine_w_m2,
            "intensity_w_sr": intensity_w_sr,
            "phase_angle_deg": phase_angle_deg,
            "range_m": range_m,
            "lit_visible_area_m2": lit_visible_area_m2,
            "eclipse": eclipse,
            "earth_blocks_view": earth_blocks_view,
        })
        if magnitude is not UNSET:
            field_dict["magnitude"] = magnitude
        if magnitude_1000km is not UNSET:
            field_dict["magnitude_1000km"] = magnitude_1000km
        if magnitude_standard is not UNSET:
            field_dict["magnitude_standard"] = magnitude_standard
        if magnitude_intrinsic is not UNSET:
            field_dict["magnitude_intrinsic"] = magnitude_intrinsic
        if azimuth_deg is not UNSET:
            field_dict["azimuth_deg"] = azimuth_deg
        if elevation_deg is not UNSET:
            field_dict["elevation_deg"] = elevation_deg
        if sun_elevation_deg is not UNSET:
            field_dict["sun_elevation_deg"] = sun_elevation_deg
        if in_earth_shadow is not UNSET:
            field_dict["in_earth_shadow"] = in_earth_shadow
        if observation is not UNSET:
            field_dict["observation"] = observation

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.observation_result import ObservationResult # noqa: PLC0415
        d = dict(src_dict)
        t = d.pop("t")

        irradiance_w_m2 = d.pop("irradiance_w_m2")

        sun_w_m2 = d.pop("sun_w_m2")

        earthshine_w_m2 = d.pop("earthshine_w_m2")

        intensity_w_sr = d.pop("intensity_w_sr")

        phase_angle_deg = d.pop("phase_angle_deg")

        range_m = d.pop("range_m")

        lit_visible_area_m2 = d.pop("lit_visible_area_m2")

        eclipse = d.pop("eclipse")

        earth_blocks_view = d.pop("earth_blocks_view")

        def _parse_magnitude(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        magnitude = _parse_magnitude(d.pop("magnitude", UNSET))


        def _parse_magnitude_1000km(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        magnitude_1000km = _parse_magnitude_1000km(d.pop("magnitude_1000km", UNSET))


        def _parse_magnitude_standard(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        magnitude_standard = _parse_magnitude_standard(d.pop("magnitude_standard", UNSET))


        def _parse_magnitude_intrinsic(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        magnitude_intrinsic = _parse_magnitude_intrinsic(d.pop("magnitude_intrinsic", UNSET))


        def _parse_azimuth_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        azimuth_deg = _parse_azimuth_deg(d.pop("azimuth_deg", UNSET))


        def _parse_elevation_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        elevation_deg = _parse_elevation_deg(d.pop("elevation_deg", UNSET))


        def _parse_sun_elevation_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        sun_elevation_deg = _parse_sun_elevation_deg(d.pop("sun_elevation_deg", UNSET))


        def _parse_in_earth_shadow(data: object) -> bool | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(bool | None | Unset, data)

        in_earth_shadow = _parse_in_earth_shadow(d.pop("in_earth_shadow", UNSET))


        def _parse_observation(data: object) -> None | ObservationResult | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                observation_type_0 = ObservationResult.from_dict(data)



                return observation_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | ObservationResult | Unset, data)

        observation = _parse_observation(d.pop("observation", UNSET))


        epoch_result = cls(
            t=t,
            irradiance_w_m2=irradiance_w_m2,
            sun_w_m2=sun_w_m2,
            earthshine_w_m2=earthshine_w_m2,
            intensity_w_sr=intensity_w_sr,
            phase_angle_deg=phase_angle_deg,
            range_m=range_m,
            lit_visible_area_m2=lit_visible_area_m2,
            eclipse=eclipse,
            earth_blocks_view=earth_blocks_view,
            magnitude=magnitude,
            magnitude_1000km=magnitude_1000km,
            magnitude_standard=magnitude_standard,
            magnitude_intrinsic=magnitude_intrinsic,
            azimuth_deg=azimuth_deg,
            elevation_deg=elevation_deg,
            sun_elevation_deg=sun_elevation_deg,
            in_earth_shadow=in_earth_shadow,
            observation=observation,
        )


        epoch_result.additional_properties = d
        return epoch_result

    @property
    def additional_keys(self) -> list[str]:
        return list(self.additional_properties.keys())

    def __getitem__(self, key: str) -> Any:
        return self.additional_properties[key]

    def __setitem__(self, key: str, value: Any) -> None:
        self.additional_properties[key] = value

    def __delitem__(self, key: str) -> None:
        del self.additional_properties[key]

    def __contains__(self, key: str) -> bool:
        return key in self.additional_properties
