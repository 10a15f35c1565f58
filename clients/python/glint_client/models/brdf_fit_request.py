from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.brdf_fit_request_fixed_type_0 import BrdfFitRequestFixedType0
  from ..models.sample import Sample





T = TypeVar("T", bound="BrdfFitRequest")



@_attrs_define
class BrdfFitRequest:
    """ The body of `POST /v1/fits/brdf`: what `glint fit-brdf` takes as a CSV file and options.

        Attributes:
            model (str): `seed-microfacet`, `rough-conductor`, `ashikhmin-shirley` or `lambert`.
            samples (list[Sample]): The measurements; at least one more than the free parameters.
            fixed (BrdfFitRequestFixedType0 | None | Unset): Parameters held at a value instead of fitted, by name (e.g.
                `{"n": 0.18, "k": 3.6}`).
            loss (None | str | Unset): `huber` (default), `cauchy` or `l2`.
            space (None | str | Unset): Residual space: `log` (default) or `linear`.
            plot (bool | None | Unset): Include the Fig. 2-style plot as SVG text in `plot_svg`. Default false.
            normalised (bool | None | Unset): `seed-microfacet` only: fit the normalised form (a request's `"normalised":
                true`),
                where km is the lobe's albedo at normal incidence and kd + km ≤ 1 is kept. Default
                false (the paper's form).
     """

    model: str
    samples: list[Sample]
    fixed: BrdfFitRequestFixedType0 | None | Unset = UNSET
    loss: None | str | Unset = UNSET
    space: None | str | Unset = UNSET
    plot: bool | None | Unset = UNSET
    normalised: bool | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.brdf_fit_request_fixed_type_0 import BrdfFitRequestFixedType0 # noqa: PLC0415
        from ..models.sample import Sample # noqa: PLC0415
        model = self.model

        samples = []
        for samples_item_data in self.samples:
            samples_item = samples_item_data.to_dict()
            samples.append(samples_item)



        fixed: dict[str, Any] | None | Unset
        if isinstance(self.fixed, Unset):
            fixed = UNSET
        elif isinstance(self.fixed, BrdfFitRequestFixedType0):
            fixed = self.fixed.to_dict()
        else:
            fixed = self.fixed

        loss: None | str | Unset
        if isinstance(self.loss, Unset):
            loss = UNSET
        else:
            loss = self.loss

        space: None | str | Unset
        if isinstance(self.space, Unset):
            space = UNSET
        else:
            space = self.space

        plot: bool | None | Unset
        if isinstance(self.plot, Unset):
            plot = UNSET
        else:
            plot = self.plot

        normalised: bool | None | Unset
        if isinstance(self.normalised, Unset):
            normalised = UNSET
        else:
            normalised = self.normalised


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "model": model,
            "samples": samples,
        })
        if fixed is not UNSET:
            field_dict["fixed"] = fixed
        if loss is not UNSET:
            field_dict["loss"] = loss
        if space is not UNSET:
            field_dict["space"] = space
        if plot is not UNSET:
            field_dict["plot"] = plot
        if normalised is not UNSET:
            field_dict["normalised"] = normalised

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.brdf_fit_request_fixed_type_0 import BrdfFitRequestFixedType0 # noqa: PLC0415
        from ..models.sample import Sample # noqa: PLC0415
        d = dict(src_dict)
        model = d.pop("model")

        samples = []
        _samples = d.pop("samples")
        for samples_item_data in (_samples):
            samples_item = Sample.from_dict(samples_item_data)



            samples.append(samples_item)


        def _parse_fixed(data: object) -> BrdfFitRequestFixedType0 | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                fixed_type_0 = BrdfFitRequestFixedType0.from_dict(data)



                return fixed_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(BrdfFitRequestFixedType0 | None | Unset, data)

        fixed = _parse_fixed(d.pop("fixed", UNSET))


        def _parse_loss(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        loss = _parse_loss(d.pop("loss", UNSET))


        def _parse_space(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        space = _parse_space(d.pop("space", UNSET))


        def _parse_plot(data: object) -> bool | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(bool | None | Unset, data)

        plot = _parse_plot(d.pop("plot", UNSET))


        def _parse_normalised(data: object) -> bool | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(bool | None | Unset, data)

        normalised = _parse_normalised(d.pop("normalised", UNSET))


        brdf_fit_request = cls(
            model=model,
            samples=samples,
            fixed=fixed,
            loss=loss,
            space=space,
            plot=plot,
            normalised=normalised,
        )

        return brdf_fit_request

