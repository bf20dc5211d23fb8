!> Unit systems of a run (&control units): the names written into the dumps'
!> units attributes and the probe files' column headers, and the factors that
!> take the material library's data (cm, g, us, Mbar) to another system.
module core_units
  use core_kinds, only: rk
  implicit none
  private
  public :: unit_of, units_valid

  !> The systems &control units accepts.
  character(len=*), parameter, public :: UNITS_CGSUS = 'cm-g-us-mbar'
  character(len=*), parameter, public :: UNITS_SI = 'si'
  character(len=*), parameter, public :: UNITS_NONE = 'none'
  character(len=*), parameter, public :: UNITS_LIST = 'cm-g-us-mbar, si, none'

  !> cm-g-us-mbar -> SI: 1 cm = 1e-2 m, 1 g = 1e-3 kg, 1 us = 1e-6 s,
  !> 1 Mbar = 1e11 Pa; derived: 1 cm/us = 1e4 m/s, 1 g/cm^3 = 1e3 kg/m^3,
  !> 1 Mbar cm^3/g = 1e8 J/kg (specific energy), 1 Mbar cm^3 = 1e5 J.
  real(rk), parameter, public :: SI_LENGTH = 1.0e-2_rk
  real(rk), parameter, public :: SI_MASS = 1.0e-3_rk
  real(rk), parameter, public :: SI_TIME = 1.0e-6_rk
  real(rk), parameter, public :: SI_PRESSURE = 1.0e11_rk
  real(rk), parameter, public :: SI_VELOCITY = 1.0e4_rk
  real(rk), parameter, public :: SI_DENSITY = 1.0e3_rk
  real(rk), parameter, public :: SI_SPECIFIC_ENERGY = 1.0e8_rk
  real(rk), parameter, public :: SI_ENERGY = 1.0e5_rk

contains

  logical function units_valid(system)
    character(len=*), intent(in) :: system
    units_valid = system == UNITS_CGSUS .or. system == UNITS_SI .or. system == UNITS_NONE
  end function units_valid

  !> The unit of a quantity in a system: quantity one of 'length', 'time',
  !> 'mass', 'velocity', 'pressure', 'density', 'specific_energy', 'energy',
  !> 'volume', 'dimensionless'. 'none' gives 'dimensionless' for all.
  function unit_of(system, quantity) result(unit)
    character(len=*), intent(in) :: system, quantity
    character(len=:), allocatable :: unit
    if (system == UNITS_NONE .or. quantity == 'dimensionless') then
      unit = 'dimensionless'
      return
    end if
    if (system == UNITS_SI) then
      select case (quantity)
      case ('length')
        unit = 'm'
      case ('time')
        unit = 's'
      case ('mass')
        unit = 'kg'
      case ('velocity')
        unit = 'm/s'
      case ('pressure')
        unit = 'Pa'
      case ('density')
        unit = 'kg/m^3'
      case ('specific_energy')
        unit = 'J/kg'
      case ('energy')
        unit = 'J'
      case ('volume')
        unit = 'm^3'
      case default
        unit = '?'
      end select
    else
      select case (quantity)
      case ('length')
        unit = 'cm'
      case ('time')
        unit = 'us'
      case ('mass')
        unit = 'g'
      case ('velocity')
        unit = 'cm/us'
      case ('pressure')
        unit = 'Mbar'
      case ('density')
        unit = 'g/cm^3'
      case ('specific_energy')
        unit = 'Mbar*cm^3/g'
      case ('energy')
        unit = 'Mbar*cm^3'
      case ('volume')
        unit = 'cm^3'
      case default
        unit = '?'
      end select
    end if
  end function unit_of

end module core_units
