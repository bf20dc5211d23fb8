!> Mie-Grueneisen equation of state with a linear Us-up Hugoniot reference,
!> in Steinberg's form (the LS-DYNA *EOS_GRUNEISEN form with S2 = S3 = 0).
!>
!> Formula implemented, with mu = rho/rho0 - 1 and E = rho0 e the internal
!> energy per unit reference volume (e = specific internal energy):
!>
!>   compression (mu > 0):
!>     p = rho0 c0^2 mu [1 + (1 - gamma0/2) mu - (b/2) mu^2] / [1 - (s1 - 1) mu]^2
!>         + (gamma0 + b mu) E
!>   expansion (mu <= 0):
!>     p = rho0 c0^2 mu + (gamma0 + b mu) E
!>
!> then p = max(p, p_min) (pressure cut-off; none by default).
!>
!> Source: D. J. Steinberg, "Equation of state and strength properties of
!> selected materials", UCRL-MA-106439 (LLNL, 1991; revised 1996), which
!> tabulates rho0, c0, s1, gamma0 and b; this is the LS-DYNA *EOS_GRUNEISEN
!> pressure with S2 = S3 = 0 and a = b (as reproduced in the IMPETUS Afea
!> manual, EOS_GRUNEISEN, and in LLNL Spheral's GruneisenEquationOfState,
!> which cites Steinberg). With b = 0 it is the textbook form
!> p = rho0 c0^2 eta (1 - gamma0 eta/2) / (1 - s1 eta)^2 + gamma0 E with
!> eta = 1 - rho0/rho = mu/(1 + mu).
!>
!> What the form means. The Grueneisen parameter is
!> Gamma(rho) = (gamma0 + b mu)/(1 + mu), i.e. rho Gamma = rho0 (gamma0 + b mu),
!> or Gamma = gamma0 (1 - eta) + b eta. The linear Us = c0 + s1 up Hugoniot
!> gives, from the Rankine-Hugoniot relations,
!>   p_H(mu) = rho0 c0^2 mu (1 + mu) / [1 - (s1 - 1) mu]^2,
!>   E_H(mu) = rho0 e_H = p_H (1 - rho0/rho)/2 = p_H mu / (2 (1 + mu)),
!> and p = p_H + (gamma0 + b mu)(E - E_H) expands exactly to the compression
!> formula above, for any b: the Hugoniot is the reference curve (the
!> -(b/2) mu^2 term is the b part of (gamma0 + b mu) E_H). The expansion branch
!> replaces the reference curve by the linear p = rho0 c0^2 mu, which matches
!> the compression branch in value and slope at mu = 0.
!>
!> The compression branch is singular at mu = 1/(s1 - 1) (for Cu, rho about
!> 3 rho0); callers must stay below it. Units are those of the data (the code
!> uses cm, g, us, Mbar).
module eos_mie_gruneisen
  use core_kinds, only: rk
  implicit none
  private
  public :: mie_gruneisen_t, mg_pressure, mg_sound_speed, mg_energy_from_pressure, &
      mg_hugoniot_pressure, MG_SOUND_SPEED_FLOOR

  !> Lower bound of the sound speed, as a fraction of c0. A zone in strong
  !> tension can have c^2 <= 0 from the formula (p rho0 (gamma0 + b mu)/rho^2
  !> negative and larger than (dp/drho)_e); it gets c = MG_SOUND_SPEED_FLOOR c0.
  real(rk), parameter :: MG_SOUND_SPEED_FLOOR = 1.0e-3_rk

  !> Material constants of the Mie-Grueneisen EOS (Steinberg's table).
  type :: mie_gruneisen_t
    real(rk) :: rho0 !< reference density
    real(rk) :: c0 !< bulk sound speed: intercept of the linear Us-up fit
    real(rk) :: s1 !< slope of the linear Us-up fit
    real(rk) :: gamma0 !< Grueneisen parameter at rho0
    real(rk) :: b = 0.0_rk !< first-order volume correction: rho Gamma = rho0 (gamma0 + b mu)
    !> pressure cut-off (spall / minimum pressure): p is limited below by p_min;
    !> the default -huge means no cut-off
    real(rk) :: p_min = -huge(1.0_rk)
  end type mie_gruneisen_t

contains

  !> Pressure from density and specific internal energy, limited below by
  !> m%p_min (see the module header for the formula and its source).
  elemental function mg_pressure(m, rho, e) result(p)
    type(mie_gruneisen_t), intent(in) :: m !< material constants
    real(rk), intent(in) :: rho !< density
    real(rk), intent(in) :: e !< specific internal energy (per unit mass)
    real(rk) :: p
    real(rk) :: mu

    mu = rho / m%rho0 - 1.0_rk
    p = zero_energy_pressure(m, mu) + (m%gamma0 + m%b * mu) * m%rho0 * e
    p = max(p, m%p_min)
  end function mg_pressure

  !> Adiabatic sound speed from c^2 = (dp/drho)_e + (p/rho^2) (dp/de)_rho, with
  !>   (dp/drho)_e = (1/rho0) dp0/dmu + b e,   (dp/de)_rho = rho0 (gamma0 + b mu),
  !> where p0(mu) = p(rho, e = 0):
  !>   compression: dp0/dmu = rho0 c0^2 [(N + mu N') D + 2 (s1 - 1) mu N] / D^3,
  !>     N = 1 + (1 - gamma0/2) mu - (b/2) mu^2, N' = 1 - gamma0/2 - b mu,
  !>     D = 1 - (s1 - 1) mu;
  !>   expansion: dp0/dmu = rho0 c0^2.
  !> The result is at least MG_SOUND_SPEED_FLOOR c0 (also for rho <= 0). In a
  !> zone on the cut-off (p = p_min) the derivatives are those of the uncut EOS
  !> (not the zero slope of the flat cut-off), combined with the p passed in.
  elemental function mg_sound_speed(m, rho, e, p) result(c)
    type(mie_gruneisen_t), intent(in) :: m !< material constants
    real(rk), intent(in) :: rho !< density
    real(rk), intent(in) :: e !< specific internal energy
    real(rk), intent(in) :: p !< the zone pressure, normally mg_pressure(m, rho, e)
    real(rk) :: c
    real(rk) :: mu, c2, c_floor

    c_floor = MG_SOUND_SPEED_FLOOR * m%c0
    if (rho <= 0.0_rk) then
      c = c_floor
      return
    end if
    mu = rho / m%rho0 - 1.0_rk
    c2 = m%c0**2 * zero_energy_slope(m, mu) + m%b * e &
        + p * m%rho0 * (m%gamma0 + m%b * mu) / rho**2
    c = sqrt(max(c2, c_floor**2))
  end function mg_sound_speed

  !> Specific internal energy for which the uncut EOS gives pressure p at
  !> density rho: e = (p - p0(mu)) / (rho0 (gamma0 + b mu)). The cut-off is not
  !> inverted. Requires gamma0 + b mu /= 0 (true for all rho > 0 when
  !> gamma0 > b >= 0, as for Steinberg's data).
  elemental function mg_energy_from_pressure(m, rho, p) result(e)
    type(mie_gruneisen_t), intent(in) :: m !< material constants
    real(rk), intent(in) :: rho !< density
    real(rk), intent(in) :: p !< pressure
    real(rk) :: e
    real(rk) :: mu

    mu = rho / m%rho0 - 1.0_rk
    e = (p - zero_energy_pressure(m, mu)) / (m%rho0 * (m%gamma0 + m%b * mu))
  end function mg_energy_from_pressure

  !> Reference (principal) Hugoniot pressure from the Rankine-Hugoniot relations
  !> with Us = c0 + s1 up: p_H(mu) = rho0 c0^2 mu (1 + mu) / (1 - (s1 - 1) mu)^2,
  !> for 0 <= mu < 1/(s1 - 1). No cut-off.
  elemental function mg_hugoniot_pressure(m, mu) result(p)
    type(mie_gruneisen_t), intent(in) :: m !< material constants
    real(rk), intent(in) :: mu !< compression rho/rho0 - 1
    real(rk) :: p

    p = m%rho0 * m%c0**2 * mu * (1.0_rk + mu) / (1.0_rk - (m%s1 - 1.0_rk) * mu)**2
  end function mg_hugoniot_pressure

  !> The uncut pressure at zero internal energy, p0(mu) = p(rho, e = 0).
  elemental function zero_energy_pressure(m, mu) result(p0)
    type(mie_gruneisen_t), intent(in) :: m
    real(rk), intent(in) :: mu !< compression rho/rho0 - 1
    real(rk) :: p0
    real(rk) :: numerator, denominator

    if (mu > 0.0_rk) then
      numerator = 1.0_rk + (1.0_rk - 0.5_rk * m%gamma0) * mu - 0.5_rk * m%b * mu**2
      denominator = 1.0_rk - (m%s1 - 1.0_rk) * mu
      p0 = m%rho0 * m%c0**2 * mu * numerator / denominator**2
    else
      p0 = m%rho0 * m%c0**2 * mu
    end if
  end function zero_energy_pressure

  !> The dimensionless slope (dp0/dmu) / (rho0 c0^2); 1 at mu = 0.
  elemental function zero_energy_slope(m, mu) result(slope)
    type(mie_gruneisen_t), intent(in) :: m
    real(rk), intent(in) :: mu !< compression rho/rho0 - 1
    real(rk) :: slope
    real(rk) :: numerator, numerator_slope, denominator

    if (mu > 0.0_rk) then
      numerator = 1.0_rk + (1.0_rk - 0.5_rk * m%gamma0) * mu - 0.5_rk * m%b * mu**2
      numerator_slope = 1.0_rk - 0.5_rk * m%gamma0 - m%b * mu
      denominator = 1.0_rk - (m%s1 - 1.0_rk) * mu
      slope = ((numerator + mu * numerator_slope) * denominator &
          + 2.0_rk * (m%s1 - 1.0_rk) * mu * numerator) / denominator**3
    else
      slope = 1.0_rk
    end if
  end function zero_energy_slope

end module eos_mie_gruneisen
