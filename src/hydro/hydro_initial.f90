!> Initial conditions per region: density, energy or pressure, uniform or
!> radial velocity u0 (r0/r)^k r_hat, and a point energy deposit.
module hydro_initial
  use core_kinds, only: rk, i8
  use core_status, only: status_t
  use core_keys, only: UNSET
  use mesh_geometry, only: hex_centroid, hex_volume
  use mesh_local, only: mesh_t
  use material_table, only: material_t, material_energy_from_pressure, EOS_MIE_GRUNEISEN
  use hydro_state, only: state_t
  use parallel_env, only: par_allgather, par_size, par_sum, par_sum_array, par_max
  implicit none
  private
  public :: initial_apply, UNSET

  !> One &region group: the zones of a block (0 = any) whose centroid is in box.
  type, public :: region_t
    integer :: block = 0 !< block index, 0 = every block
    real(rk) :: box(6) = [-huge(1.0_rk), huge(1.0_rk), -huge(1.0_rk), huge(1.0_rk), &
        -huge(1.0_rk), huge(1.0_rk)] !< xmin xmax ymin ymax zmin zmax
    real(rk) :: density = UNSET
    real(rk) :: energy = UNSET !< specific internal energy
    real(rk) :: pressure = UNSET
    real(rk) :: velocity(3) = 0.0_rk !< uniform velocity
    real(rk) :: radial_u0 = 0.0_rk !< radial speed at r0 (negative = inward)
    real(rk) :: radial_r0 = 1.0_rk
    real(rk) :: radial_k = 0.0_rk
    real(rk) :: center(3) = 0.0_rk !< centre of the radial field
    real(rk) :: deposit_energy = 0.0_rk !< energy put in the zone nearest deposit_point
    real(rk) :: deposit_point(3) = 0.0_rk
  end type region_t

contains

  pure logical function inside(box, c)
    real(rk), intent(in) :: box(6), c(3)
    inside = c(1) >= box(1) .and. c(1) <= box(2) .and. c(2) >= box(3) .and. c(2) <= box(4) &
        .and. c(3) >= box(5) .and. c(3) <= box(6)
  end function inside

  !> Set density, energy, masses and velocities; zone_material maps zones to
  !> materials. Needs node positions; leaves pressure to the caller's EOS pass.
  !> A zone that no region gives a density gets its material's reference
  !> density rho0 (Mie-Gruneisen); one whose material has none (ideal gas) is
  !> an error naming its block (block_names) and material.
  subroutine initial_apply(regions, materials, zone_material, mesh, state, status, block_names)
    type(region_t), intent(in) :: regions(:)
    type(material_t), intent(in) :: materials(:)
    integer, intent(in) :: zone_material(:)
    type(mesh_t), intent(in) :: mesh
    type(state_t), intent(inout) :: state
    type(status_t), intent(inout) :: status
    character(len=*), intent(in), optional :: block_names(:) !< per block, for messages
    real(rk), allocatable :: centroid(:, :), record(:), all(:, :), missing_block(:)
    logical, allocatable :: node_in(:)
    real(rk) :: xz(3, 8), r(3), rn, best(2), missing
    integer :: ir, z, k, n, nrank, j, nblock
    character(len=32) :: text
    character(len=80) :: label
    integer(i8) :: best_gid

    allocate(centroid(3, mesh%nzone))
    do z = 1, mesh%nzone
      do k = 1, 8
        xz(:, k) = state%node_position(:, mesh%zone_node(k, z))
      end do
      centroid(:, z) = hex_centroid(xz)
      state%zone_volume(z) = hex_volume(xz)
    end do
    state%zone_density = UNSET
    state%zone_energy = 0.0_rk
    do ir = 1, size(regions)
      do z = 1, mesh%nzone
        if (.not. selected(z)) cycle
        if (regions(ir)%density /= UNSET) state%zone_density(z) = regions(ir)%density
        if (regions(ir)%energy /= UNSET) state%zone_energy(z) = regions(ir)%energy
        if (regions(ir)%pressure /= UNSET .and. state%zone_density(z) /= UNSET) &
            state%zone_energy(z) = material_energy_from_pressure( &
            materials(zone_material(z)), state%zone_density(z), regions(ir)%pressure)
      end do
    end do
    ! The material's reference density where no region gives one.
    do z = 1, mesh%nzone
      if (state%zone_density(z) /= UNSET) cycle
      if (materials(zone_material(z))%eos /= EOS_MIE_GRUNEISEN) cycle
      if (materials(zone_material(z))%mg%rho0 > 0.0_rk) &
          state%zone_density(z) = materials(zone_material(z))%mg%rho0
    end do
    missing = real(count(state%zone_density(1:mesh%nzone_owned) == UNSET), rk)
    if (par_sum(missing) > 0.0_rk) then
      nblock = 0
      if (mesh%nzone > 0) nblock = maxval(mesh%zone_block(1:mesh%nzone))
      nblock = par_max(nblock)
      allocate(missing_block(nblock))
      missing_block = 0.0_rk
      do z = 1, mesh%nzone_owned
        if (state%zone_density(z) == UNSET) missing_block(mesh%zone_block(z)) = &
            missing_block(mesh%zone_block(z)) + 1.0_rk
      end do
      call par_sum_array(missing_block)
      do k = 1, nblock
        if (missing_block(k) == 0.0_rk) cycle
        write(text, '(i0)') nint(missing_block(k))
        if (present(block_names)) then
          write(label, '(a)') 'block '''//trim(block_names(k))//''''
        else
          write(label, '(a,i0)') 'block ', k
        end if
        call status%add('&region: density: '//trim(text)//' zones of '//trim(label)// &
            ' get no density from any region, and their material '''// &
            trim(material_of_block(k))//''' has no reference density (ideal gas): '// &
            'give density in a region that covers them')
      end do
      return
    end if
    state%zone_mass = state%zone_density * state%zone_volume

    ! Velocities of owned nodes (their zones are all local); ghosts by halo.
    allocate(node_in(mesh%nnode))
    do ir = 1, size(regions)
      node_in = .false.
      do z = 1, mesh%nzone
        if (selected(z)) node_in(mesh%zone_node(:, z)) = .true.
      end do
      do n = 1, mesh%nnode_owned
        if (.not. node_in(n)) cycle
        state%node_velocity(:, n) = regions(ir)%velocity
        if (regions(ir)%radial_u0 /= 0.0_rk) then
          r = state%node_position(:, n) - regions(ir)%center
          rn = norm2(r)
          if (rn > 0.0_rk) state%node_velocity(:, n) = state%node_velocity(:, n) + &
              regions(ir)%radial_u0 * (regions(ir)%radial_r0 / rn)**regions(ir)%radial_k * r / rn
        end if
      end do
    end do

    ! Point deposits: the owned zone nearest the point, ties to the lowest id.
    nrank = par_size()
    allocate(record(2), all(2, nrank))
    do ir = 1, size(regions)
      if (regions(ir)%deposit_energy == 0.0_rk) cycle
      best = [huge(1.0_rk), huge(1.0_rk)]
      do z = 1, mesh%nzone_owned
        rn = norm2(centroid(:, z) - regions(ir)%deposit_point)
        if (rn < best(1) .or. (rn == best(1) .and. real(mesh%zone_gid(z), rk) < best(2))) &
            best = [rn, real(mesh%zone_gid(z), rk)]
      end do
      record = best
      call par_allgather(record, all)
      best = all(:, 1)
      do j = 2, nrank
        if (all(1, j) < best(1) .or. (all(1, j) == best(1) .and. all(2, j) < best(2))) &
            best = all(:, j)
      end do
      best_gid = int(best(2), i8)
      do z = 1, mesh%nzone
        if (mesh%zone_gid(z) == best_gid) state%zone_energy(z) = state%zone_energy(z) + &
            regions(ir)%deposit_energy / state%zone_mass(z)
      end do
    end do

  contains

    !> The material of a block's zones (on any rank), for the message.
    function material_of_block(b) result(name)
      integer, intent(in) :: b
      character(len=:), allocatable :: name
      real(rk) :: m
      integer :: zz
      m = 0.0_rk
      do zz = 1, mesh%nzone_owned
        if (mesh%zone_block(zz) == b) then
          m = real(zone_material(zz), rk)
          exit
        end if
      end do
      m = par_max(m)
      name = '?'
      if (m > 0.0_rk) name = trim(materials(nint(m))%name)
    end function material_of_block

    logical function selected(zz)
      integer, intent(in) :: zz
      selected = (regions(ir)%block == 0 .or. regions(ir)%block == mesh%zone_block(zz)) &
          .and. inside(regions(ir)%box, centroid(:, zz))
    end function selected

  end subroutine initial_apply

end module hydro_initial
