from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.fitted_epoch import FittedEpoch
  from ..models.lightcurve_fit_parameters import LightcurveFitParameters
  from ..models.lightcurve_fit_start import LightcurveFitStart
  from ..models.lightcurve_fit_uncertainty import LightcurveFitUncertainty
  from ..models.request import Request
  from ..models.solver_report import SolverReport





T = TypeVar("T", bound="LightcurveFit")



@_attrs_define
class LightcurveFit:
    """ The result of a light-curve fit.

        Attributes:
            parameters (LightcurveFitParameters): Fitted value of each free parameter, by path.
            uncertainty (LightcurveFitUncertainty): 1σ of each (same units), from s²(JᵀJ)⁻¹ at the optimum; `null` where the
                light
                curve does not determine it.
            start (LightcurveFitStart): Where each started.
            at_bound (list[str]): Parameters that ended on a bound.
            chi2 (float): χ² = Σ ((m_obs − m_fit)/σ)².
            dof (int): Observations − free parameters.
            chi2_dof (float): χ²/dof (≈ 1 when the model explains the curve within its errors).
            rms_mag (float): RMS of m_obs − m_fit, mag.
            observations (int): Observations used.
            correlation (list[list[float | None]]): Correlations of the fitted parameters, in the order of
                `correlation_order`.
            correlation_order (list[str]):
            curve (list[FittedEpoch]): Per observation: t (s), observed magnitude, σ, fitted magnitude (`null`: no light).
            request (Request): A light-curve request: one object, its epochs, and how it is lit.
            warnings (list[str]):
            solver (SolverReport): What a fit reports about how its solver went.
     """

    parameters: LightcurveFitParameters
    uncertainty: LightcurveFitUncertainty
    start: LightcurveFitStart
    at_bound: list[str]
    chi2: float
    dof: int
    chi2_dof: float
    rms_mag: float
    observations: int
    correlation: list[list[float | None]]
    correlation_order: list[str]
    curve: list[FittedEpoch]
    request: Request
    warnings: list[str]
    solver: SolverReport
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.fitted_epoch import FittedEpoch # noqa: PLC0415
        from ..models.lightcurve_fit_parameters import LightcurveFitParameters # noqa: PLC0415
        from ..models.lightcurve_fit_start import LightcurveFitStart # noqa: PLC0415
        from ..models.lightcurve_fit_uncertainty import LightcurveFitUncertainty # noqa: PLC0415
        from ..models.request import Request # noqa: PLC0415
        from ..models.solver_report import SolverReport # noqa: PLC0415
        parameters = self.parameters.to_dict()

        uncertainty = self.uncertainty.to_dict()

        start = self.start.to_dict()

        at_bound = self.at_bound



        chi2 = self.chi2

        dof = self.dof

        chi2_dof = self.chi2_dof

        rms_mag = self.rms_mag

        observations = self.observations

        correlation = []
        for correlation_item_data in self.correlation:
            correlation_item = []
            for correlation_item_item_data in correlation_item_data:
                correlation_item_item: float | None
                correlation_item_item = correlation_item_item_data
                correlation_item.append(correlation_item_item)


            correlation.append(correlation_item)



        correlation_order = self.correlation_order



        curve = []
        for curve_item_data in self.curve:
            curve_item = curve_item_data.to_dict()
            curve.append(curve_item)



        request = self.request.to_dict()

        warnings = self.warnings



        solver = self.solver.to_dict()


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "parameters": parameters,
            "uncertainty": uncertainty,
            "start": start,
            "at_bound": at_bound,
            "chi2": chi2,
            "dof": dof,
            "chi2_dof": chi2_dof,
            "rms_mag": rms_mag,
            "observations": observations,
            "correlation": correlation,
            "correlation_order": correlation_order,
            "curve": curve,
            "request": request,
            "warnings": warnings,
            "solver": solver,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.fitted_epoch import FittedEpoch # noqa: PLC0415
        from ..models.lightcurve_fit_parameters import LightcurveFitParameters # noqa: PLC0415
        from ..models.lightcurve_fit_start import LightcurveFitStart # noqa: PLC0415
        from ..models.lightcurve_fit_uncertainty import LightcurveFitUncertainty # noqa: PLC0415
        from ..models.request import Request # noqa: PLC0415
        from ..models.solver_report import SolverReport # noqa: PLC0415
        d = dict(src_dict)
        parameters = LightcurveFitParameters.from_dict(d.pop("parameters"))




        uncertainty = LightcurveFitUncertainty.from_dict(d.pop("uncertainty"))




        start = LightcurveFitStart.from_dict(d.pop("start"))




        at_bound = cast(list[str], d.pop("at_bound"))


        chi2 = d.pop("chi2")

        dof = d.pop("dof")

        chi2_dof = d.pop("chi2_dof")

        rms_mag = d.pop("rms_mag")

        observations = d.pop("observations")

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


        curve = []
        _curve = d.pop("curve")
        for curve_item_data in (_curve):
            curve_item = FittedEpoch.from_dict(curve_item_data)



            curve.append(curve_item)


        request = Request.from_dict(d.pop("request"))




        warnings = cast(list[str], d.pop("warnings"))


        solver = SolverReport.from_dict(d.pop("solver"))




        lightcurve_fit = cls(
            parameters=parameters,
            uncertainty=uncertainty,
            start=start,
            at_bound=at_bound,
            chi2=chi2,
            dof=dof,
            chi2_dof=chi2_dof,
            rms_mag=rms_mag,
            observations=observations,
            correlation=correlation,
            correlation_order=correlation_order,
            curve=curve,
            request=request,
            warnings=warnings,
            solver=solver,
        )


        lightcurve_fit.additional_properties = d
        return lightcurve_fit

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
