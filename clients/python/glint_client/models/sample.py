from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="Sample")



@_attrs_define
class Sample:
    """ One BRDF measurement.

        Attributes:
            theta_i_deg (float): Incidence zenith angle θi, degrees, 0 ≤ θi < 90.
            theta_r_deg (float): Reflection (detector) zenith angle θr, degrees, 0 ≤ θr < 90.
            phi_deg (float): Relative azimuth φ, degrees, −360..360; 180 is the forward side of the plane of
                incidence (the mirror direction at θr = θi), 0 the backward side.
            brdf_sr (float): The measured BRDF, sr⁻¹ (≥ 0).
            weight (float | None | Unset): Relative weight (> 0; default 1): its squared residual counts this many times
                (1/σ² for a known error σ in the residual space).
            wavelength_um (float | None | Unset): Wavelength, µm (> 0), informative: every model here is grey.
     """

    theta_i_deg: float
    theta_r_deg: float
    phi_deg: float
    brdf_sr: float
    weight: float | None | Unset = UNSET
    wavelength_um: float | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        theta_i_deg = self.theta_i_deg

        theta_r_deg = self.theta_r_deg

        phi_deg = self.phi_deg

        brdf_sr = self.brdf_sr

        weight: float | None | Unset
        if isinstance(self.weight, Unset):
            weight = UNSET
        else:
            weight = self.weight

        wavelength_um: float | None | Unset
        if isinstance(self.wavelength_um, Unset):
            wavelength_um = UNSET
        else:
            wavelength_um = self.wavelength_um


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "theta_i_deg": theta_i_deg,
            "theta_r_deg": theta_r_deg,
            "phi_deg": phi_deg,
            "brdf_sr": brdf_sr,
        })
        if weight is not UNSET:
            field_dict["weight"] = weight
        if wavelength_um is not UNSET:
            field_dict["wavelength_um"] = wavelength_um

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        theta_i_deg = d.pop("theta_i_deg")

        theta_r_deg = d.pop("theta_r_deg")

        phi_deg = d.pop("phi_deg")

        brdf_sr = d.pop("brdf_sr")

        def _parse_weight(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        weight = _parse_weight(d.pop("weight", UNSET))


        def _parse_wavelength_um(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        wavelength_um = _parse_wavelength_um(d.pop("wavelength_um", UNSET))


        sample = cls(
            theta_i_deg=theta_i_deg,
            theta_r_deg=theta_r_deg,
            phi_deg=phi_deg,
            brdf_sr=brdf_sr,
            weight=weight,
            wavelength_um=wavelength_um,
        )

        return sample

