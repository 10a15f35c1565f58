from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="FittedEpoch")



@_attrs_define
class FittedEpoch:
    """ One observation and the fitted model there.

        Attributes:
            t (float):
            observed (float):
            sigma (float):
            fitted (float | None | Unset):
     """

    t: float
    observed: float
    sigma: float
    fitted: float | None | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        t = self.t

        observed = self.observed

        sigma = self.sigma

        fitted: float | None | Unset
        if isinstance(self.fitted, Unset):
            fitted = UNSET
        else:
            fitted = self.fitted


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "t": t,
            "observed": observed,
            "sigma": sigma,
        })
        if fitted is not UNSET:
            field_dict["fitted"] = fitted

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        t = d.pop("t")

        observed = d.pop("observed")

        sigma = d.pop("sigma")

        def _parse_fitted(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        fitted = _parse_fitted(d.pop("fitted", UNSET))


        fitted_epoch = cls(
            t=t,
            observed=observed,
            sigma=sigma,
            fitted=fitted,
        )


        fitted_epoch.additional_properties = d
        return fitted_epoch

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
