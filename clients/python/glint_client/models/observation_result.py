from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="ObservationResult")



@_attrs_define
class ObservationResult:
    """ A telescope's counts of the object at one epoch (the CCD equation, docs/physics.md
    §10a). S = Φ·10^(−0.4kX)·A·t·q·τ·f_ap; N = √(S + sky + dark + n_pix·σ_R²).

        Attributes:
            signal_e (float): The object's electrons in the photometric aperture, S.
            sky_e (float): The sky's electrons in the aperture.
            dark_e (float): Dark-current electrons in the aperture.
            pixels (float): Pixels in the aperture, π r² / s².
            noise_e (float): Noise in the aperture, e⁻: √(S + sky + dark + pixels·read_noise²).
            snr (float): Signal-to-noise ratio S / N (0 when there is neither signal nor noise).
            signal_adu (float): The signal in ADU, S / gain.
            peak_pixel_e (float): Electrons on the brightest pixel (the image centred on it, plus sky and dark).
            saturated (bool): The brightest pixel reaches the full well.
            sample_e (float): A noisy measurement of S: Poisson(S + sky + dark) plus normal read noise, less the
                expected sky and dark, drawn with the request's seed.
            sample_magnitude (float | None | Unset): The sample as a magnitude in the band, m − 2.5 log10(sample / S);
                `null` when the
                sample is not positive or there is no magnitude.
     """

    signal_e: float
    sky_e: float
    dark_e: float
    pixels: float
    noise_e: float
    snr: float
    signal_adu: float
    peak_pixel_e: float
    saturated: bool
    sample_e: float
    sample_magnitude: float | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        signal_e = self.signal_e

        sky_e = self.sky_e

        dark_e = self.dark_e

        pixels = self.pixels

        noise_e = self.noise_e

        snr = self.snr

        signal_adu = self.signal_adu

        peak_pixel_e = self.peak_pixel_e

        saturated = self.saturated

        sample_e = self.sample_e

        sample_magnitude: float | None | Unset
        if isinstance(self.sample_magnitude, Unset):
            sample_magnitude = UNSET
        else:
            sample_magnitude = self.sample_magnitude


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "signal_e": signal_e,
            "sky_e": sky_e,
            "dark_e": dark_e,
            "pixels": pixels,
            "noise_e": noise_e,
            "snr": snr,
            "signal_adu": signal_adu,
            "peak_pixel_e": peak_pixel_e,
            "saturated": saturated,
            "sample_e": sample_e,
        })
        if sample_magnitude is not UNSET:
            field_dict["sample_magnitude"] = sample_magnitude

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        signal_e = d.pop("signal_e")

        sky_e = d.pop("sky_e")

        dark_e = d.pop("dark_e")

        pixels = d.pop("pixels")

        noise_e = d.pop("noise_e")

        snr = d.pop("snr")

        signal_adu = d.pop("signal_adu")

        peak_pixel_e = d.pop("peak_pixel_e")

        saturated = d.pop("saturated")

        sample_e = d.pop("sample_e")

        def _parse_sample_magnitude(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        sample_magnitude = _parse_sample_magnitude(d.pop("sample_magnitude", UNSET))


        observation_result = cls(
            signal_e=signal_e,
            sky_e=sky_e,
            dark_e=dark_e,
            pixels=pixels,
            noise_e=noise_e,
            snr=snr,
            signal_adu=signal_adu,
            peak_pixel_e=peak_pixel_e,
            saturated=saturated,
            sample_e=sample_e,
            sample_magnitude=sample_magnitude,
        )


        observation_result.additional_properties = d
        return observation_result

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
