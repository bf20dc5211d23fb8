!> The deck's unit-mistake checks: the limits and the wording shared by the
!> packages that check a density (material_deck, hydro_deck) or a speed
!> (io_deck_checks, app_checks).
!>
!> * A density more than DENSITY_FACTOR times from the material's reference
!>   density rho0 (above or below) is refused: no solid or liquid is
!>   compressed 10-fold at t = 0, and the factors of the usual mistakes are
!>   1000 (kg/m^3 given in a g/cm^3 deck) and 1/1000.
!> * An initial node speed above 10 cm/us = 100 km/s (SPEED_LIMIT_CGSUS, the
!>   same speed in SI) is refused unless &control allow_high_speed: impacts
!>   are below about 10 km/s, and a speed in m/s given in a cm-g-us deck is
!>   1e4 times too large (1 km/s = 1000 m/s reads as 1000 cm/us).
!>   Dimensionless decks (units = 'none') are not checked.
module core_unit_checks
  use core_kinds, only: rk
  use core_units, only: UNITS_SI, UNITS_NONE, UNITS_CGSUS, SI_VELOCITY
  implicit none
  private
  public :: brief_text, speed_limit, speed_limit_text, density_ratio_text, density_mistake, speed_mistake

  real(rk), parameter, public :: DENSITY_FACTOR = 10.0_rk
  real(rk), parameter, public :: SPEED_LIMIT_CGSUS = 10.0_rk !< cm/us

contains

  !> A real in 5 significant digits, no blanks ('2703.0', '2.7030', '0.12000E-03').
  function brief_text(value) result(text)
    real(rk), intent(in) :: value
    character(len=:), allocatable :: text
    character(len=32) :: buffer
    write(buffer, '(g0.5)') value
    text = trim(adjustl(buffer))
  end function brief_text

  !> The largest initial node speed accepted in the unit system, 0 for none
  !> (no check).
  pure real(rk) function speed_limit(units)
    character(len=*), intent(in) :: units
    select case (units)
    case (UNITS_SI)
      speed_limit = SPEED_LIMIT_CGSUS * SI_VELOCITY
    case (UNITS_NONE)
      speed_limit = 0.0_rk
    case default
      speed_limit = SPEED_LIMIT_CGSUS
    end select
  end function speed_limit

  !> '10 cm/us (100 km/s)' or '1e5 m/s (100 km/s)'.
  function speed_limit_text(units) result(text)
    character(len=*), intent(in) :: units
    character(len=:), allocatable :: text
    if (units == UNITS_SI) then
      text = '1e5 m/s (100 km/s)'
    else
      text = '10 cm/us (100 km/s)'
    end if
  end function speed_limit_text

  !> The likely mistake behind a speed above the limit.
  function speed_mistake(units) result(text)
    character(len=*), intent(in) :: units
    character(len=:), allocatable :: text
    if (units == UNITS_SI) then
      text = 'impacts are below about 1e4 m/s: a speed in mm/s or cm/s in an SI deck?'
    else
      text = 'impacts are below about 1 cm/us (10 km/s): a speed in m/s in a '// &
          UNITS_CGSUS//' deck? (1000 m/s = 0.1 cm/us)'
    end if
  end function speed_mistake

  !> '1000 times' / '1/1000 of' wording of value/reference.
  function density_ratio_text(ratio) result(text)
    real(rk), intent(in) :: ratio
    character(len=:), allocatable :: text
    character(len=32) :: buffer
    if (ratio >= 1.0_rk) then
      write(buffer, '(i0)') nint(ratio)
      text = trim(adjustl(buffer))//' times'
    else
      write(buffer, '(i0)') nint(1.0_rk / ratio)
      text = '1/'//trim(adjustl(buffer))//' of'
    end if
  end function density_ratio_text

  !> The likely mistake behind a density value/reference = ratio far from 1.
  function density_mistake(units, ratio) result(text)
    character(len=*), intent(in) :: units
    real(rk), intent(in) :: ratio
    character(len=:), allocatable :: text
    real(rk) :: decades
    decades = log10(ratio)
    if (units /= UNITS_SI .and. units /= UNITS_NONE .and. abs(decades - 3.0_rk) < 0.5_rk) then
      text = 'a density in kg/m^3 (SI) in a '//UNITS_CGSUS//' deck? (1 g/cm^3 = 1000 kg/m^3)'
    else if (units == UNITS_SI .and. abs(decades + 3.0_rk) < 0.5_rk) then
      text = 'a density in g/cm^3 in an SI deck? (1 g/cm^3 = 1000 kg/m^3)'
    else
      text = 'check the units of the deck (&control units = '''//trim(units)//''')'
    end if
  end function density_mistake

end module core_unit_checks
