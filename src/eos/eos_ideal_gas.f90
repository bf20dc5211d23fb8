!> Ideal-gas equation of state, p = (gamma - 1) rho e.
module eos_ideal_gas
  use core_kinds, only: rk
  implicit none
  private
  public :: ideal_gas_pressure, ideal_gas_sound_speed, ideal_gas_energy

contains

  !> Pressure from density and specific internal energy. A gas holds no
  !> tension: a (round-off) negative energy of a cold zone gives p = 0.
  elemental function ideal_gas_pressure(gamma, rho, e) result(p)
    real(rk), intent(in) :: gamma !< ratio of specific heats
    real(rk), intent(in) :: rho !< density
    real(rk), intent(in) :: e !< specific internal energy
    real(rk) :: p
    p = (gamma - 1.0_rk) * rho * max(e, 0.0_rk)
  end function ideal_gas_pressure

  !> Adiabatic sound speed; zero for a cell with no mass or negative pressure.
  elemental function ideal_gas_sound_speed(gamma, rho, p) result(c)
    real(rk), intent(in) :: gamma, rho, p
    real(rk) :: c
    if (rho > 0.0_rk) then
      c = sqrt(gamma * max(p, 0.0_rk) / rho)
    else
      c = 0.0_rk
    end if
  end function ideal_gas_sound_speed

  !> Specific internal energy from density and pressure.
  elemental function ideal_gas_energy(gamma, rho, p) result(e)
    real(rk), intent(in) :: gamma, rho, p
    real(rk) :: e
    e = p / ((gamma - 1.0_rk) * rho)
  end function ideal_gas_energy

end module eos_ideal_gas
