!> history.txt: one `# ` header line naming the whitespace-separated
!> columns, a row for cycle 0, then one row per history_every cycles (energy,
!> momentum, boundary and contact work, the energy balance, and per contact
!> interface its diagnostic columns `<name>_<quantity>`, then per material
!> `<material>_internal`, `_kinetic`, `_plastic_work`, `_hourglass`). Rank 0
!> writes it.
module io_history
  use core_kinds, only: rk, i8
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use hydro_driver, only: hydro_energies, hydro_material_energies
  use contact_enforce, only: contact_t, CONTACT_DIAG_COUNT, CONTACT_DIAG_NAMES
  use parallel_env, only: par_rank, par_sum_array
  use io_deck, only: config_t
  implicit none
  private
  public :: history_open, history_write, relative_error

  !> Per-material columns, in the order of hydro_material_energies' sums.
  character(len=*), parameter :: MATERIAL_COLUMNS(4) = [character(len=12) :: 'internal', &
      'kinetic', 'plastic_work', 'hourglass']

contains

  !> history.txt: a fresh file, or on restart the lines up to the restart cycle.
  subroutine history_open(config, state, restarted)
    type(config_t), intent(in) :: config
    type(state_t), intent(in) :: state
    logical, intent(in) :: restarted
    integer :: unit, ios, n, k, j
    character(len=4096) :: line
    character(len=4096), allocatable :: keep(:)
    character(len=:), allocatable :: header
    integer(i8) :: c
    character(len=:), allocatable :: path
    logical :: exists
    if (par_rank() /= 0) return
    path = trim(config%output%directory)//'/history.txt'
    allocate(keep(0))
    inquire(file=path, exist=exists)
    if (restarted .and. exists) then
      open(newunit=unit, file=path, status='old', action='read')
      read(unit, '(a)', iostat=ios) line
      do
        read(unit, '(a)', iostat=ios) line
        if (ios /= 0) exit
        read(line, *, iostat=ios) c
        if (ios == 0 .and. c <= state%cycle) keep = [character(len=len(line)) :: keep, line]
      end do
      close(unit)
    end if
    open(newunit=unit, file=path, status='replace', action='write')
    header = '# cycle time dt internal_energy kinetic_energy boundary_work '// &
        'total_energy energy_error momentum_x momentum_y momentum_z contact_work'
    do k = 1, size(config%contacts)
      do j = 1, CONTACT_DIAG_COUNT
        header = header//' '//trim(config%contacts(k)%name)//'_'//trim(CONTACT_DIAG_NAMES(j))
      end do
    end do
    do k = 1, size(config%materials)
      do j = 1, size(MATERIAL_COLUMNS)
        header = header//' '//trim(config%materials(k)%name)//'_'//trim(MATERIAL_COLUMNS(j))
      end do
    end do
    write(unit, '(a)') header
    do n = 1, size(keep)
      write(unit, '(a)') trim(keep(n))
    end do
    close(unit)
  end subroutine history_open

  subroutine history_write(config, mesh, state, ct)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(contact_t), intent(in) :: ct
    real(rk) :: sums(5), total
    real(rk), allocatable :: per_material(:, :), flat(:)
    integer, allocatable :: zone_material(:)
    integer :: unit, k, z
    call hydro_energies(mesh, state, sums)
    call par_sum_array(sums)
    allocate(zone_material(mesh%nzone), per_material(4, size(config%materials)))
    do z = 1, mesh%nzone
      zone_material(z) = config%blocks(mesh%zone_block(z))%material
    end do
    call hydro_material_energies(mesh, state, zone_material, per_material)
    flat = reshape(per_material, [size(per_material)])
    call par_sum_array(flat)
    if (par_rank() /= 0) return
    total = sums(1) + sums(2)
    open(newunit=unit, file=trim(config%output%directory)//'/history.txt', status='old', &
        position='append', action='write')
    write(unit, '(i0,10(1x,es23.15e3))', advance='no') state%cycle, state%time, state%dt, &
        sums(1), sums(2), state%boundary_work, total, relative_error(total, state, ct%work), sums(3:5)
    write(unit, '(1x,es23.15e3)', advance='no') ct%work
    do k = 1, ct%ndeck
      write(unit, '(*(1x,es23.15e3))', advance='no') ct%pairs(k)%diag
    end do
    write(unit, '(*(1x,es23.15e3))', advance='no') flat
    write(unit, '(a)') ''
    close(unit)
  end subroutine history_write

  real(rk) function relative_error(total, state, contact_work)
    real(rk), intent(in) :: total
    type(state_t), intent(in) :: state
    real(rk), intent(in) :: contact_work !< work of the contact forces so far
    relative_error = (total - state%boundary_work - contact_work - &
        state%energy_initial) / &
        max(abs(state%energy_initial), tiny(1.0_rk))
  end function relative_error

end module io_history
