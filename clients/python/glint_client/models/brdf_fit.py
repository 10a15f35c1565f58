from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.brdf_fit_fixed import BrdfFitFixed
  from ..models.brdf_fit_material import BrdfFitMaterial
  from ..models.brdf_fit_parameters import BrdfFitParameters
  from ..models.brdf_fit_uncertainty import BrdfFitUncertainty
  from ..models.solver_report import SolverReport





T = TypeVar("T", bound="BrdfFit")



@_attrs_define
class BrdfFit:
    """ The result of a BRDF fit.

        Attributes:
            model (str): The model fitted.
            parameters (BrdfFitParameters): Every parameter of the model, fitted or fixed, under the name a request's
                material
                takes (paste them into `object.materials[..]` with this `model`).
            uncertainty (BrdfFitUncertainty): 1σ of each fitted parameter (same units), from s²(JᵀJ)⁻¹ at the optimum;
                `null`
                where the samples do not determine it.
            fixed (BrdfFitFixed): The parameters held fixed.
            at_bound (list[str]): Fitted parameters that ended on a bound (their uncertainty is then one-sided).
            material (BrdfFitMaterial): A material object ready for a request (named `fitted`).
            rms (float): RMS of f_model − f_meas over the samples, sr⁻¹ (unweighted).
            residual_sd (float): Residual standard deviation per degree of freedom in the fit's space, s.
            samples (int): Samples used.
            dof (int): Degrees of freedom: samples − fitted parameters.
            outliers (int): Samples the robust loss weighted below ½ (outliers).
            space (str): Residual space: `log` or `linear`.
            albedo (float): Directional-hemispherical albedo of the fitted material at normal incidence.
            correlation (list[list[float | None]]): Correlations of the fitted parameters, in the order of
                `correlation_order`.
            correlation_order (list[str]):
            wavelengths_um (list[float]): Distinct wavelengths in the samples, µm.
            warnings (list[str]): Things to know about this fit.
            solver (SolverReport): What a fit reports about how its solver went.
            rms_log (float | None | Unset): RMS of ln(f_model / f_meas) over the samples where both are positive (≈ relative
                RMS); `null` when there is none.
            normalised (bool | Unset): Whether the seed model was fitted in its normalised form (km the lobe's albedo at
                normal incidence, kd + km ≤ 1); absent when not.
            plot_svg (None | str | Unset): The plot (SVG text) when the request asked for it.
     """

    model: str
    parameters: BrdfFitParameters
    uncertainty: BrdfFitUncertainty
    fixed: BrdfFitFixed
    at_bound: list[str]
    material: BrdfFitMaterial
    rms: float
    residual_sd: float
    samples: int
    dof: int
    outliers: int
    space: str
    albedo: float
    correlation: list[list[float | None]]
    correlation_order: list[str]
    wavelengths_um: list[float]
    warnings: list[str]
    solver: SolverReport
    rms_log: float | None | Unset = UNSET
    normalised: bool | Unset = UNSET
    plot_svg: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.brdf_fit_fixed import BrdfFitFixed # noqa: PLC0415
        from ..models.brdf_fit_material import BrdfFitMaterial # noqa: PLC0415
        from ..models.brdf_fit_parameters import BrdfFitParameters # noqa: PLC0415
        from ..models.brdf_fit_uncertainty import BrdfFitUncertainty # noqa: PLC0415
        from ..models.solver_report import SolverReport # noqa: PLC0415
        model = self.model

        parameters = self.parameters.to_dict()

        uncertainty = self.uncertainty.to_dict()

        fixed = self.fixed.to_dict()

        at_bound = self.at_bound



        material = self.material.to_dict()

        rms = self.rms

        residual_sd = self.residual_sd

        samples = self.samples

        dof = self.dof

        outliers = self.outliers

        space = self.space

        albedo = self.albedo

        correlation = []
        for correlation_item_data in self.correlation:
            correlation_item = []
            for correlation_item_item_data in correlation_item_data:
                correlation_item_item: float | None
                correlation_item_item = correlation_item_item_data
                correlation_item.append(correlation_item_item)


            correlation.append(correlation_item)



        correlation_order = self.correlation_order



        wavelengths_um = self.wavelengths_um



        warnings = self.warnings



        solver = self.solver.to_dict()

        rms_log: float | None | Unset
        if isinstance(self.rms_log, Unset):
            rms_log = UNSET
        else:
            rms_log = self.rms_log

        normalised = self.normalised

        plot_svg: None | str | Unset
        if isinstance(self.plot_svg, Unset):
            plot_svg = UNSET
        else:
            plot_svg = self.plot_svg


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "model": model,
            "parameters": parameters,
            "uncertainty": uncertainty,
            "fixed": fixed,
            "at_bound": at_bound,
            "material": material,
            "rms": rms,
            "residual_sd": residual_sd,
            "samples": samples,
            "dof": dof,
            "outliers": outliers,
            "space": space,
            "albedo": albedo,
            "correlation": correlation,
            "correlation_order": correlation_order,
            "wavelengths_um": wavelengths_um,
            "warnings": warnings,
            "solver": solver,
        })
        if rms_log is not UNSET:
            field_dict["rms_log"] = rms_log
        if normalised is not UNSET:
            field_dict["normalised"] = normalised
        if plot_svg is not UNSET:
            field_dict["plot_svg"] = plot_svg

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.brdf_fit_fixed import BrdfFitFixed # noqa: PLC0415
        from ..models.brdf_fit_material import BrdfFitMaterial # noqa: PLC0415
        from ..models.brdf_fit_parameters import BrdfFitParameters # noqa: PLC0415
        from ..models.brdf_fit_uncertainty import BrdfFitUncertainty # noqa: PLC0415
        from ..models.solver_report import SolverReport # noqa: PLC0415
        d = dict(src_dict)
        model = d.pop("model")

        parameters = BrdfFitParameters.from_dict(d.pop("parameters"))




        uncertainty = BrdfFitUncertainty.from_dict(d.pop("uncertainty"))




        fixed = BrdfFitFixed.from_dict(d.pop("fixed"))




        at_bound = cast(list[str], d.pop("at_bound"))


        material = BrdfFitMaterial.from_dict(d.pop("material"))




        rms = d.pop("rms")

        residual_sd = d.pop("residual_sd")

        samples = d.pop("samples")

        dof = d.pop("dof")

        outliers = d.pop("outliers")

        space = d.pop("space")

        albedo = d.pop("albedo")

        correlation = []
        _correlation = d.pop("correlation")
        for correlation_item_data in (_correlation):
            correlation_item = []
            _correlation_item = correlation_item_data
            for correlation_item_item_data in (_correlation_item):
                def _parse_correlation_item_item(data: object) -> float | None:
                    if data is None:
                        return data
                    return cast(float | None, data)

                correlation_item_item = _parse_correlation_item_item(correlation_item_item_data)

                correlation_item.append(correlation_item_item)

            correlation.append(correlation_item)


        correlation_order = cast(list[str], d.pop("correlation_order"))


        wavelengths_um = cast(list[float], d.pop("wavelengths_um"))


        warnings = cast(list[str], d.pop("warnings"))


        solver = SolverReport.from_dict(d.pop("solver"))




        def _parse_rms_log(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        rms_log = _parse_rms_log(d.pop("rms_log", UNSET))


        normalised = d.pop("normalised", UNSET)

        def _parse_plot_svg(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        plot_svg = _parse_plot_svg(d.pop("plot_svg", UNSET))


        brdf_fit = cls(
            model=model,
            parameters=parameters,
            uncertainty=uncertainty,
            fixed=fixed,
            at_bound=at_bound,
            material=material,
            rms=rms,
            residual_sd=residual_sd,
            samples=samples,
            dof=dof,
            outliers=outliers,
            space=space,
            albedo=albedo,
            correlation=correlation,
            correlation_order=correlation_order,
            wavelengths_um=wavelengths_um,
            warnings=warnings,
            solver=solver,
            rms_log=rms_log,
            normalised=normalised,
            plot_svg=plot_svg,
        )


        brdf_fit.additional_properties = d
        return brdf_fit

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
