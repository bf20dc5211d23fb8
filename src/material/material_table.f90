!> Material table: one entry per named material, with its equation of state.
!> A new EOS is a new kernel module plus one case in material_eos.
module material_table
  use core_kinds, only: rk
  use eos_ideal_gas, only: ideal_gas_pressure, ideal_gas_sound_speed, ideal_gas_energy
  implicit none
  private
  public :: material_eos, material_energy_from_pressure

  integer, parameter, public :: EOS_IDEAL_GAS = 1
  integer, parameter, public :: MATERIAL_NAME_LEN = 32

  !> One material.
  type, public :: material_t
    character(len=MATERIAL_NAME_LEN) :: name = '' !< deck name
    integer :: eos = EOS_IDEAL_GAS !< EOS_* code
    real(rk) :: gamma = 1.4_rk !< ideal gas: ratio of specific heats
  end type material_t

contains

  !> Pressure and sound speed of the zones in list(:) made of material mat.
  subroutine material_eos(mat, list, density, energy, pressure, sound_speed)
    type(material_t), intent(in) :: mat
    integer, intent(in) :: list(:) !< zones of this material
    real(rk), intent(in) :: density(:), energy(:)
    real(rk), intent(inout) :: pressure(:), sound_speed(:)
    integer :: i, z
    select case (mat%eos)
    case (EOS_IDEAL_GAS)
      do i = 1, size(list)
        z = list(i)
        pressure(z) = ideal_gas_pressure(mat%gamma, density(z), energy(z))
        sound_speed(z) = ideal_gas_sound_speed(mat%gamma, density(z), pressure(z))
      end do
    end select
  end subroutine material_eos

  !> Specific internal energy that gives pressure p at density rho.
  elemental function material_energy_from_pressure(mat, rho, p) result(e)
    type(material_t), intent(in) :: mat
    real(rk), intent(in) :: rho, p
    real(rk) :: e
    select case (mat%eos)
    case (EOS_IDEAL_GAS)
      e = ideal_gas_energy(mat%gamma, rho, p)
    case default
      e = 0.0_rk
    end select
  end function material_energy_from_pressure

end module material_table
