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
  use core_exact_sum, only: exact_sum_t, exact_value
  use contact_enforce, only: contact_t, CONTACT_DIAG_COUNT, CONTACT_DIAG_NAMES
  use parallel_env, only: par_rank, par_sum_exact
  use io_deck, only: config_t
  use io_rows, only: rows_restart
  implicit none
  private
  public :: history_open, history_write, history_sums, relative_error

  !> Per-material columns, in the order of history_sums' per_material.
  character(len=*), parameter :: MATERIAL_COLUMNS(4) = [character(len=12) :: 'internal', &
      'kinetic', 'plastic_work', 'hourglass']

contains

  !> history.txt: a fresh file, or on restart the lines up to the restart cycle
  !> (streamed: linear in the file's length, rows of any width).
  subroutine history_open(config, state, restarted)
    type(config_t), intent(in) :: config
    type(state_t), intent(in) :: state
    logical, intent(in) :: restarted
    integer :: k, j
    character(len=:), allocatable :: header
    if (par_rank() /= 0) return
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
    call rows_restart(trim(config%output%directory)//'/history.txt', header, restarted, ' ', &
        state%cycle)
  end subroutine history_open

  subroutine history_write(config, mesh, state, ct)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    type(contact_t), intent(in) :: ct
    real(rk) :: sums(5), total
    real(rk), allocatable :: per_material(:, :), flat(:)
    integer :: unit, k
    allocate(per_material(4, size(config%materials)))
    call history_sums(config, mesh, state, sums, per_material)
    flat = reshape(per_material, [size(per_material)])
    if (par_rank() /= 0) return
    total = sums(1) + sums(2)
    open(newunit=unit, file=trim(config%output%directory)//'/history.txt', status='old', &
        position='append', action='write')
    write(unit, '(i0,10(1x,es23.15e3))', advance='no') state%cycle, state%time, state%dt, &
        sums(1), sums(2), state%boundary_work, total, relative_error(total, state), sums(3:5)
    write(unit, '(1x,es23.15e3)', advance='no') state%contact_work
    do k = 1, ct%ndeck
      write(unit, '(*(1x,es23.15e3))', advance='no') ct%pairs(k)%diag
    end do
    write(unit, '(*(1x,es23.15e3))', advance='no') flat
    write(unit, '(a)') ''
    close(unit)
  end subroutine history_write

  !> The history's global sums, exact (core_exact_sum) so that they are
  !> bitwise the same on any rank count: sums = internal energy, kinetic
  !> energy, momentum x, y, z (owned zones and nodes; the terms of
  !> hydro_energies); per_material(:, m) = internal, kinetic (each corner's
  !> eighth of the zone mass at its node's velocity), plastic work,
  !> hourglass work of the owned zones of material m (the terms of
  !> hydro_material_energies). Collective.
  subroutine history_sums(config, mesh, state, sums, per_material)
    type(config_t), intent(in) :: config
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(in) :: state
    real(rk), intent(out) :: sums(5)
    real(rk), intent(out) :: per_material(:, :) !< (4, nmaterial)
    type(exact_sum_t), allocatable :: acc(:)
    integer :: z, n, m, k, nm
    real(rk) :: v2
    nm = size(config%materials)
    allocate(acc(5 + 4 * nm))
    associate(v => state%node_velocity, mass => state%node_mass)
      do z = 1, mesh%nzone_owned
        call acc(1)%add(state%zone_mass(z) * state%zone_energy(z))
      end do
      do n = 1, mesh%nnode_owned
        call acc(2)%add(0.5_rk * mass(n) * (v(1, n) * v(1, n) + v(2, n) * v(2, n) &
            + v(3, n) * v(3, n)))
        call acc(3)%add(mass(n) * v(1, n))
        call acc(4)%add(mass(n) * v(2, n))
        call acc(5)%add(mass(n) * v(3, n))
      end do
      do z = 1, mesh%nzone_owned
        m = 5 + 4 * (config%blocks(mesh%zone_block(z))%material - 1)
        call acc(m + 1)%add(state%zone_mass(z) * state%zone_energy(z))
        v2 = 0.0_rk
        do k = 1, 8
          n = mesh%zone_node(k, z)
          v2 = v2 + (v(1, n) * v(1, n) + v(2, n) * v(2, n) + v(3, n) * v(3, n))
        end do
        call acc(m + 2)%add(0.0625_rk * state%zone_mass(z) * v2)
        if (allocated(state%zone_plastic_work)) call acc(m + 3)%add(state%zone_plastic_work(z))
        if (allocated(state%zone_hourglass_work)) &
            call acc(m + 4)%add(state%zone_hourglass_work(z))
      end do
    end associate
    call par_sum_exact(acc)
    do k = 1, 5
      sums(k) = exact_value(acc(k))
    end do
    do m = 1, nm
      do k = 1, 4
        per_material(k, m) = exact_value(acc(5 + 4 * (m - 1) + k))
      end do
    end do
  end subroutine history_sums

  real(rk) function relative_error(total, state)
    real(rk), intent(in) :: total
    type(state_t), intent(in) :: state
    relative_error = (total - state%boundary_work - state%contact_work - &
        state%energy_initial) / &
        max(abs(state%energy_initial), tiny(1.0_rk))
  end function relative_error

end module io_history
