from enum import StrEnum

class ShadowingSpec(StrEnum):
    CORRELATED = "correlated"
    SEPARABLE = "separable"

    def __str__(self) -> str:
        return str(self.value)
