from enum import StrEnum

class JobKind(StrEnum):
    FIT_LIGHTCURVE = "fit-lightcurve"
    LIGHTCURVE = "lightcurve"

    def __str__(self) -> str:
        return str(self.value)
