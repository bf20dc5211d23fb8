!> HDF5 dumps (collective, one hyperslab per rank after a block
!> redistribution) with the layout of docs/design.md section 6, their XDMF
!> sidecars, the time-series XDMF, and restart reading.
module io_dump
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use core_units, only: unit_of
  use core_text, only: to_text
  use mesh_local, only: mesh_t
  use hydro_state, only: state_t
  use io_h5, only: hid_t, h5_create_file, h5_open_file, h5_close_file, h5_write_real_rows, &
      h5_write_real_vector, h5_write_int_rows, h5_write_int_vector, h5_write_attr_real, &
      h5_write_attr_int, h5_write_attr_string, h5_read_real_rows, h5_read_real_vector, &
      h5_read_attr_real, h5_read_attr_int, h5_read_attr_string, h5_dataset_rows, h5_create_group, &
      h5_path_exists, IO_H5_OK, IO_H5_ERR_NOT_FOUND
  use parallel_env, only: par_rank, par_size, par_comm_handle, par_info_null_handle, par_max, &
      par_io_info_handle
  implicit none
  private
  public :: dump_write, dump_read, dump_read_deck, dump_series_update

  integer, parameter, public :: FORMAT_VERSION = 1
  !> Longest deck text stored in a dump (an HDF5 attribute's header space).
  integer, parameter, public :: DECK_TEXT_MAX = 60000

  !> Run metadata that may differ between runs; written under /run only.
  type, public :: run_info_t
    real(rk) :: wall_seconds = 0.0_rk
    character(len=32) :: reason = 'scheduled' !< why the dump was written
    character(len=:), allocatable :: version !< of the program
    character(len=:), allocatable :: command !< the command line
    character(len=:), allocatable :: deck !< the deck file's text
  end type run_info_t

contains

  !> Write the dump file path (and its .xmf sidecar) of the current state.
  !> units is the run's unit system (&control units): the root attribute
  !> units, and each field's units attribute from it.
  subroutine dump_write(path, title, units, block_names, mesh, state, info, status, &
      contact_gap, contact_work, pair_work, contact_active, contact_resume, contact_offset)
    character(len=*), intent(in) :: path, title, units, block_names
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(in) :: state
    type(run_info_t), intent(in) :: info
    type(status_t), intent(inout) :: status
    !> (nnode local) the contact audit's gaps (absent: no contact)
    real(rk), intent(in), optional :: contact_gap(:)
    real(rk), intent(in), optional :: contact_work !< work of the contact forces so far
    real(rk), intent(in), optional :: pair_work(:) !< the same per contact interface
    !> (nnode local) per node the interfaces it carried force of in the last
    !> step, bit k - 1 for interface k (restart state of the contact)
    real(rk), intent(in), optional :: contact_active(:)
    !> the contact's search schedule and last audit (contact_resume_state)
    real(rk), intent(in), optional :: contact_resume(:)
    !> (ndeck, nnode local) the offsets of the contact nodes once a refresh
    !> measured some (contact_offset_values; no rows: none to keep)
    real(rk), intent(in), optional :: contact_offset(:, :)
    real(rk), allocatable :: nblockk(:, :)
    real(rk) :: work
    integer(hid_t) :: file
    integer :: ierr, e, nno, nzo, z, k
    integer(i8) :: node_first, zone_first
    character(len=400) :: msg
    real(rk), allocatable :: nblock3(:, :), nblock1(:, :), zblock(:, :), zlocal(:, :)
    integer(ik), allocatable :: connectivity(:, :), cblock(:, :)

    msg = ''
    ierr = 0
    e = 0
    nno = mesh%nnode_owned
    nzo = mesh%nzone_owned
    node_first = mesh%node_io%first - 1
    zone_first = mesh%zone_io%first - 1
    call h5_create_file(path, par_comm_handle(), par_io_info_handle(), file, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (.not. agreed()) return

    call h5_write_attr_int(file, '/', 'format_version', FORMAT_VERSION, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_write_attr_real(file, '/', 'time', state%time, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_write_attr_int(file, '/', 'cycle', int(state%cycle, ik), e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_write_attr_string(file, '/', 'title', title, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_write_attr_string(file, '/', 'units', units, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e

    ! Mesh. The connectivity first, before the other buffers exist, and
    ! redistributed four corners at a time: the largest transient of a dump
    ! (the global ids, the exchange's two buffers and the block) stays below
    ! the set-up's peak memory (docs/benchmarks.md, memory).
    allocate(cblock(8, mesh%zone_io%nblock))
    allocate(connectivity(4, nzo))
    do k = 1, 5, 4
      do z = 1, nzo
        connectivity(:, z) = int(mesh%node_gid(mesh%zone_node(k:k + 3, z)) - 1, ik)
      end do
      call mesh%zone_io%to_block_int(connectivity, cblock(k:k + 3, :))
    end do
    deallocate(connectivity)
    call h5_write_int_rows(file, '/mesh/connectivity', cblock, mesh%nzone_global, zone_first, &
        e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    ! With erosion: the connectivity the XDMF shows, an eroded zone collapsed
    ! onto its first node (a cell of no extent, so ParaView draws only the
    ! live zones and every zone field keeps its row).
    if (allocated(state%zone_alive)) then
      allocate(connectivity(8, nzo))
      do z = 1, nzo
        connectivity(:, z) = int(mesh%node_gid(mesh%zone_node(:, z)) - 1, ik)
        if (state%zone_alive(z) == 0.0_rk) connectivity(:, z) = connectivity(1, z)
      end do
      call mesh%zone_io%to_block_int(connectivity, cblock)
      deallocate(connectivity)
      call h5_write_int_rows(file, '/mesh/live_connectivity', cblock, mesh%nzone_global, &
          zone_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
    end if
    call mesh%zone_io%to_block_int(reshape(mesh%zone_block(1:nzo), [1, nzo]), cblock(1:1, :))
    call h5_write_int_vector(file, '/mesh/block', cblock(1, :), mesh%nzone_global, &
        zone_first, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    deallocate(cblock)
    allocate(nblock3(3, mesh%node_io%nblock), nblock1(1, mesh%node_io%nblock))
    allocate(zblock(1, mesh%zone_io%nblock), zlocal(1, nzo))
    call mesh%node_io%to_block(state%node_position(:, 1:nno), nblock3)
    call h5_write_real_rows(file, '/mesh/coordinates', nblock3, mesh%nnode_global, &
        node_first, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call units_of('/mesh/coordinates', 'length')
    call h5_write_attr_string(file, '/mesh', 'block_names', block_names, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e

    ! Nodes.
    call mesh%node_io%to_block(state%node_velocity(:, 1:nno), nblock3)
    call h5_write_real_rows(file, '/nodes/velocity', nblock3, mesh%nnode_global, node_first, &
        e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call units_of('/nodes/velocity', 'velocity')
    ! Derived: displacement from the positions at t = 0.
    if (allocated(state%node_position_initial)) then
      call mesh%node_io%to_block(state%node_position(:, 1:nno) - &
          state%node_position_initial(:, 1:nno), nblock3)
      call h5_write_real_rows(file, '/nodes/displacement', nblock3, mesh%nnode_global, &
          node_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call units_of('/nodes/displacement', 'length')
    end if
    call mesh%node_io%to_block(reshape(state%node_mass(1:nno), [1, nno]), nblock1)
    call h5_write_real_vector(file, '/nodes/mass', nblock1(1, :), mesh%nnode_global, &
        node_first, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call units_of('/nodes/mass', 'mass')
    if (present(contact_gap)) then
      call mesh%node_io%to_block(reshape(contact_gap(1:nno), [1, nno]), nblock1)
      call h5_write_real_vector(file, '/nodes/contact_gap', nblock1(1, :), mesh%nnode_global, &
          node_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call units_of('/nodes/contact_gap', 'length')
    end if

    ! Zones.
    call zone_field('/zones/density', state%zone_density, 'density')
    call zone_field('/zones/specific_internal_energy', state%zone_energy, 'specific_energy')
    call zone_field('/zones/pressure', state%zone_pressure, 'pressure')
    call zone_field('/zones/viscosity', state%zone_viscosity, 'pressure')
    call zone_field('/zones/sound_speed', state%zone_sound_speed, 'velocity')
    call zone_field('/zones/volume', state%zone_volume, 'volume')
    call zone_field('/zones/mass', state%zone_mass, 'mass')

    if (allocated(state%zone_stress)) then
      call zone_field('/zones/plastic_strain', state%zone_plastic_strain, 'dimensionless')
      deallocate(zblock)
      allocate(zblock(6, mesh%zone_io%nblock))
      call mesh%zone_io%to_block(state%zone_stress(:, 1:nzo), zblock)
      call h5_write_real_rows(file, '/zones/deviatoric_stress', zblock, mesh%nzone_global, &
          zone_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call units_of('/zones/deviatoric_stress', 'pressure')
      deallocate(zblock)
      allocate(zblock(1, mesh%zone_io%nblock))
      ! Derived: the von Mises stress sqrt(3/2 s:s) (0 in zones of materials
      ! without strength, whose deviatoric stress is 0).
      call zone_field('/zones/von_mises_stress', von_mises(state%zone_stress(:, 1:nzo)), &
          'pressure')
    end if

    ! Failure and erosion.
    if (allocated(state%zone_damage)) call zone_field('/zones/damage', state%zone_damage, &
        'dimensionless')
    if (allocated(state%zone_alive)) call zone_field('/zones/alive', state%zone_alive, &
        'dimensionless')

    ! Restart-only state.
    call h5_create_group(file, '/restart', e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_write_attr_real(file, '/restart', 'dt_previous', state%dt_previous, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_write_attr_real(file, '/restart', 'cycle', real(state%cycle, rk), e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (allocated(state%zone_hourglass)) then
      deallocate(zblock)
      allocate(zblock(12, mesh%zone_io%nblock))
      call mesh%zone_io%to_block(reshape(state%zone_hourglass(:, :, 1:nzo), [12, nzo]), zblock)
      call h5_write_real_rows(file, '/restart/hourglass_stress', zblock, mesh%nzone_global, &
          zone_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
    end if
    if (allocated(state%node_position_initial)) then
      call mesh%node_io%to_block(state%node_position_initial(:, 1:nno), nblock3)
      call h5_write_real_rows(file, '/restart/initial_position', nblock3, mesh%nnode_global, &
          node_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call units_of('/restart/initial_position', 'length')
    end if

    if (present(contact_resume)) then
      do k = 1, size(contact_resume)
        call h5_write_attr_real(file, '/restart', 'contact_resume_'//to_text(k), &
            contact_resume(k), e, msg)
        if (e /= 0 .and. ierr == 0) ierr = e
      end do
    end if
    if (present(contact_active)) then
      if (size(contact_active) > 0) then
        call mesh%node_io%to_block(reshape(contact_active(1:nno), [1, nno]), nblock1)
        call h5_write_real_vector(file, '/restart/contact_active', nblock1(1, :), &
            mesh%nnode_global, node_first, e, msg)
        if (e /= 0 .and. ierr == 0) ierr = e
      end if
    end if
    if (present(contact_offset)) then
      if (size(contact_offset, 1) > 0) then
        allocate(nblockk(size(contact_offset, 1), mesh%node_io%nblock))
        call mesh%node_io%to_block(contact_offset(:, 1:nno), nblockk)
        call h5_write_real_rows(file, '/restart/contact_offset', nblockk, mesh%nnode_global, &
            node_first, e, msg)
        if (e /= 0 .and. ierr == 0) ierr = e
      end if
    end if
    if (allocated(state%zone_alive)) then
      call h5_write_attr_real(file, '/restart', 'dt_reference', state%dt_reference, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call mesh%node_io%to_block(reshape(state%node_eroded_kinetic(1:nno), [1, nno]), nblock1)
      call h5_write_real_vector(file, '/restart/eroded_kinetic', nblock1(1, :), &
          mesh%nnode_global, node_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call units_of('/restart/eroded_kinetic', 'energy')
    end if
    if (state%stop_kinetic_initial > 0.0_rk) then
      call h5_write_attr_real(file, '/restart', 'stop_kinetic_initial', &
          state%stop_kinetic_initial, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
    end if

    ! Energy bookkeeping per zone (the history's per-material columns).
    if (allocated(state%zone_plastic_work)) call zone_field('/restart/plastic_work', &
        state%zone_plastic_work, 'energy')
    if (allocated(state%zone_hourglass_work)) call zone_field('/restart/hourglass_work', &
        state%zone_hourglass_work, 'energy')

    ! Run metadata (differs between runs; never compared).
    call h5_create_group(file, '/run', e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_write_attr_int(file, '/run', 'ranks', par_size(), e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_write_attr_real(file, '/run', 'wall_seconds', info%wall_seconds, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_write_attr_real(file, '/run', 'boundary_work', state%boundary_work, e, msg)
    work = 0.0_rk
    if (present(contact_work)) work = contact_work
    call h5_write_attr_real(file, '/run', 'contact_work', work, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    ! Each contact interface's work (a sum over the ranks' nodes, like the
    ! total: its last bits depend on the rank count, hence here).
    if (present(pair_work)) then
      do k = 1, size(pair_work)
        call h5_write_attr_real(file, '/run', 'contact_work_'//to_text(k), &
            pair_work(k), e, msg)
        if (e /= 0 .and. ierr == 0) ierr = e
      end do
    end if
    call h5_write_attr_real(file, '/run', 'energy_initial', state%energy_initial, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_write_attr_string(file, '/run', 'reason', info%reason, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (allocated(info%version)) then
      call h5_write_attr_string(file, '/run', 'version', info%version, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
    end if
    if (allocated(info%command)) then
      call h5_write_attr_string(file, '/run', 'command', info%command, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
    end if
    if (allocated(info%deck)) then
      call h5_write_attr_string(file, '/run', 'deck', &
          info%deck(1:min(len(info%deck), DECK_TEXT_MAX)), e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
    end if
    if (.not. agreed()) return
    call h5_close_file(file, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (.not. agreed()) return
    if (par_rank() == 0) call write_sidecar(path, title, mesh%nnode_global, mesh%nzone_global, &
        state%time, allocated(state%zone_stress), present(contact_gap), &
        allocated(state%zone_damage), allocated(state%zone_alive))

  contains

    subroutine zone_field(name, field, quantity)
      character(len=*), intent(in) :: name
      real(rk), intent(in) :: field(:)
      character(len=*), intent(in) :: quantity !< for its units attribute (core_units)
      zlocal(1, :) = field(1:nzo)
      call mesh%zone_io%to_block(zlocal, zblock(1:1, :))
      call h5_write_real_vector(file, name, zblock(1, :), mesh%nzone_global, zone_first, &
          e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call units_of(name, quantity)
    end subroutine zone_field

    !> The units attribute of a dataset.
    subroutine units_of(name, quantity)
      character(len=*), intent(in) :: name, quantity
      call h5_write_attr_string(file, name, 'units', unit_of(units, quantity), e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
    end subroutine units_of

    logical function agreed()
      integer :: worst
      worst = par_max(abs(ierr))
      agreed = worst == 0
      if (.not. agreed) then
        if (ierr /= 0) then
          call status%add('dump '''//trim(path)//''': '//trim(msg))
        else
          call status%add('dump '''//trim(path)//''': failed on another rank')
        end if
      end if
    end function agreed

  end subroutine dump_write

  !> The von Mises stress sqrt(3/2 s:s) of deviatoric stresses s (xx, yy, zz,
  !> xy, yz, zx; the formula of the strength update's equivalent stress).
  pure function von_mises(s) result(vm)
    real(rk), intent(in) :: s(:, :) !< (6, n)
    real(rk) :: vm(size(s, 2))
    integer :: z
    do z = 1, size(s, 2)
      vm(z) = sqrt(1.5_rk * (s(1, z)**2 + s(2, z)**2 + s(3, z)**2 &
          + 2.0_rk * (s(4, z)**2 + s(5, z)**2 + s(6, z)**2)))
    end do
  end function von_mises

  !> XDMF sidecar for one dump, so that ParaView and VisIt open it directly.
  subroutine write_sidecar(path, title, nnode, nzone, time, strength, contact, damage, alive)
    character(len=*), intent(in) :: path, title
    integer(i8), intent(in) :: nnode, nzone
    real(rk), intent(in) :: time
    logical, intent(in) :: strength !< the dump has deviatoric stress and plastic strain
    logical, intent(in) :: contact !< the dump has the contact audit's gaps
    logical, intent(in) :: damage !< the dump has the failure damage
    logical, intent(in) :: alive !< the dump has the zones' liveness (erosion)
    integer :: unit
    character(len=:), allocatable :: base
    base = basename(path)
    open(newunit=unit, file=xmf_name(path), status='replace', action='write')
    write(unit, '(a)') '<?xml version="1.0" ?>'
    write(unit, '(a)') '<Xdmf Version="3.0">'
    write(unit, '(a)') ' <Domain>'
    call write_grid(unit, base, title, nnode, nzone, time, strength, contact, damage, alive)
    write(unit, '(a)') ' </Domain>'
    write(unit, '(a)') '</Xdmf>'
    close(unit)
  end subroutine write_sidecar

  !> One <Grid> element describing a dump file (path relative to the .xmf).
  !> With erosion (alive) the topology is /mesh/live_connectivity: eroded
  !> zones collapsed to a point, so only the live zones show.
  subroutine write_grid(unit, h5file, title, nnode, nzone, time, strength, contact, damage, &
      alive)
    integer, intent(in) :: unit
    character(len=*), intent(in) :: h5file, title
    integer(i8), intent(in) :: nnode, nzone
    real(rk), intent(in) :: time
    logical, intent(in) :: strength, contact, damage, alive
    character(len=32) :: nn, nz, ts
    integer :: i
    character(len=*), parameter :: zone_fields(7) = [character(len=24) :: 'density', &
        'specific_internal_energy', 'pressure', 'viscosity', 'sound_speed', 'volume', 'mass']
    write(nn, '(i0)') nnode
    write(nz, '(i0)') nzone
    write(ts, '(es24.16)') time
    write(unit, '(a)') '  <Grid Name="'//trim(xml_escape(title))//'" GridType="Uniform">'
    write(unit, '(a)') '   <Time Value="'//trim(adjustl(ts))//'"/>'
    write(unit, '(a)') '   <Topology TopologyType="Hexahedron" NumberOfElements="'//trim(nz)//'">'
    write(unit, '(a)') '    <DataItem Dimensions="'//trim(nz)//' 8" NumberType="Int" '// &
        'Precision="4" Format="HDF">'//h5file//':/mesh/'// &
        trim(merge('live_connectivity', 'connectivity     ', alive))//'</DataItem>'
    write(unit, '(a)') '   </Topology>'
    write(unit, '(a)') '   <Geometry GeometryType="XYZ">'
    write(unit, '(a)') '    <DataItem Dimensions="'//trim(nn)//' 3" NumberType="Float" '// &
        'Precision="8" Format="HDF">'//h5file//':/mesh/coordinates</DataItem>'
    write(unit, '(a)') '   </Geometry>'
    write(unit, '(a)') '   <Attribute Name="velocity" AttributeType="Vector" Center="Node">'
    write(unit, '(a)') '    <DataItem Dimensions="'//trim(nn)//' 3" NumberType="Float" '// &
        'Precision="8" Format="HDF">'//h5file//':/nodes/velocity</DataItem>'
    write(unit, '(a)') '   </Attribute>'
    write(unit, '(a)') '   <Attribute Name="displacement" AttributeType="Vector" Center="Node">'
    write(unit, '(a)') '    <DataItem Dimensions="'//trim(nn)//' 3" NumberType="Float" '// &
        'Precision="8" Format="HDF">'//h5file//':/nodes/displacement</DataItem>'
    write(unit, '(a)') '   </Attribute>'
    if (contact) then
      write(unit, '(a)') '   <Attribute Name="contact_gap" AttributeType="Scalar" Center="Node">'
      write(unit, '(a)') '    <DataItem Dimensions="'//trim(nn)//'" NumberType="Float" '// &
          'Precision="8" Format="HDF">'//h5file//':/nodes/contact_gap</DataItem>'
      write(unit, '(a)') '   </Attribute>'
    end if
    write(unit, '(a)') '   <Attribute Name="block" AttributeType="Scalar" Center="Cell">'
    write(unit, '(a)') '    <DataItem Dimensions="'//trim(nz)//'" NumberType="Int" '// &
        'Precision="4" Format="HDF">'//h5file//':/mesh/block</DataItem>'
    write(unit, '(a)') '   </Attribute>'
    do i = 1, size(zone_fields)
      write(unit, '(a)') '   <Attribute Name="'//trim(zone_fields(i))// &
          '" AttributeType="Scalar" Center="Cell">'
      write(unit, '(a)') '    <DataItem Dimensions="'//trim(nz)//'" NumberType="Float" '// &
          'Precision="8" Format="HDF">'//h5file//':/zones/'//trim(zone_fields(i))//'</DataItem>'
      write(unit, '(a)') '   </Attribute>'
    end do
    if (strength) then
      write(unit, '(a)') '   <Attribute Name="plastic_strain" AttributeType="Scalar" Center="Cell">'
      write(unit, '(a)') '    <DataItem Dimensions="'//trim(nz)//'" NumberType="Float" '// &
          'Precision="8" Format="HDF">'//h5file//':/zones/plastic_strain</DataItem>'
      write(unit, '(a)') '   </Attribute>'
      ! Components xx, yy, zz, xy, yz, zx (not XDMF's Tensor6 order): a 6-vector.
      write(unit, '(a)') '   <Attribute Name="deviatoric_stress" AttributeType="Matrix" '// &
          'Center="Cell">'
      write(unit, '(a)') '    <DataItem Dimensions="'//trim(nz)//' 6" NumberType="Float" '// &
          'Precision="8" Format="HDF">'//h5file//':/zones/deviatoric_stress</DataItem>'
      write(unit, '(a)') '   </Attribute>'
      write(unit, '(a)') '   <Attribute Name="von_mises_stress" AttributeType="Scalar" '// &
          'Center="Cell">'
      write(unit, '(a)') '    <DataItem Dimensions="'//trim(nz)//'" NumberType="Float" '// &
          'Precision="8" Format="HDF">'//h5file//':/zones/von_mises_stress</DataItem>'
      write(unit, '(a)') '   </Attribute>'
    end if
    if (damage) call scalar_cell('damage')
    if (alive) call scalar_cell('alive')
    write(unit, '(a)') '  </Grid>'

  contains

    subroutine scalar_cell(name)
      character(len=*), intent(in) :: name
      write(unit, '(a)') '   <Attribute Name="'//name//'" AttributeType="Scalar" Center="Cell">'
      write(unit, '(a)') '    <DataItem Dimensions="'//trim(nz)//'" NumberType="Float" '// &
          'Precision="8" Format="HDF">'//h5file//':/zones/'//name//'</DataItem>'
      write(unit, '(a)') '   </Attribute>'
    end subroutine scalar_cell

  end subroutine write_grid

  function xml_escape(text) result(out)
    character(len=*), intent(in) :: text
    character(len=:), allocatable :: out
    integer :: i
    out = ''
    do i = 1, len_trim(text)
      select case (text(i:i))
      case ('<')
        out = out//'&lt;'
      case ('>')
        out = out//'&gt;'
      case ('&')
        out = out//'&amp;'
      case ('"')
        out = out//'&quot;'
      case default
        out = out//text(i:i)
      end select
    end do
  end function xml_escape

  function basename(path) result(base)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: base
    base = trim(path(index(path, '/', back=.true.) + 1:))
  end function basename

  function xmf_name(path) result(name)
    character(len=*), intent(in) :: path
    character(len=:), allocatable :: name
    integer :: dot
    dot = index(path, '.h5', back=.true.)
    if (dot > 0) then
      name = path(1:dot - 1)//'.xmf'
    else
      name = trim(path)//'.xmf'
    end if
  end function xmf_name

  !> Rank 0: add a dump to the index file series_path.dumps (dropping entries at
  !> or after its cycle, as after a restart) and rewrite the time-series XDMF.
  subroutine dump_series_update(series_path, dump_path, title, cycle, time, nnode, nzone, &
      strength, contact, damage, alive)
    character(len=*), intent(in) :: series_path !< without extension
    character(len=*), intent(in) :: dump_path, title
    integer(i8), intent(in) :: cycle
    real(rk), intent(in) :: time
    integer(i8), intent(in) :: nnode, nzone
    logical, intent(in) :: strength, contact
    logical, intent(in) :: damage, alive !< the dumps have damage, liveness (erosion)
    integer :: unit, ios, n, i
    integer(i8), allocatable :: cycles(:)
    real(rk), allocatable :: times(:)
    character(len=256), allocatable :: files(:)
    integer(i8) :: c
    real(rk) :: t
    character(len=256) :: f
    logical :: exists

    if (par_rank() /= 0) return
    ! Count the existing entries, then keep those before this cycle.
    n = 0
    inquire(file=series_path//'.dumps', exist=exists)
    if (exists) then
      open(newunit=unit, file=series_path//'.dumps', status='old', action='read')
      do
        read(unit, *, iostat=ios) c, t, f
        if (ios /= 0) exit
        n = n + 1
      end do
      close(unit)
    end if
    allocate(cycles(n + 1), times(n + 1), files(n + 1))
    n = 0
    if (exists) then
      open(newunit=unit, file=series_path//'.dumps', status='old', action='read')
      do
        read(unit, *, iostat=ios) c, t, f
        if (ios /= 0) exit
        if (c >= cycle) cycle
        n = n + 1
        cycles(n) = c
        times(n) = t
        files(n) = f
      end do
      close(unit)
    end if
    n = n + 1
    cycles(n) = cycle
    times(n) = time
    files(n) = basename(dump_path)
    open(newunit=unit, file=series_path//'.dumps', status='replace', action='write')
    do i = 1, n
      write(unit, '(i0,1x,es24.16,1x,a)') cycles(i), times(i), trim(files(i))
    end do
    close(unit)
    open(newunit=unit, file=series_path//'.xmf', status='replace', action='write')
    write(unit, '(a)') '<?xml version="1.0" ?>'
    write(unit, '(a)') '<Xdmf Version="3.0">'
    write(unit, '(a)') ' <Domain>'
    write(unit, '(a)') ' <Grid Name="series" GridType="Collection" CollectionType="Temporal">'
    do i = 1, n
      call write_grid(unit, trim(files(i)), title, nnode, nzone, times(i), strength, contact, &
          damage, alive)
    end do
    write(unit, '(a)') ' </Grid>'
    write(unit, '(a)') ' </Domain>'
    write(unit, '(a)') '</Xdmf>'
    close(unit)
  end subroutine dump_series_update

  !> The deck text stored in a dump's /run group (found false for a dump
  !> written before it was stored). Collective; the same on every rank.
  subroutine dump_read_deck(path, text, found, status)
    character(len=*), intent(in) :: path
    character(len=:), allocatable, intent(out) :: text
    logical, intent(out) :: found
    type(status_t), intent(inout) :: status
    integer(hid_t) :: file
    integer :: ierr, e
    character(len=400) :: msg
    character(len=:), allocatable :: buffer
    logical :: exists

    msg = ''
    ierr = 0
    found = .false.
    text = ''
    call h5_open_file(path, par_comm_handle(), par_info_null_handle(), file, e, msg)
    if (e /= 0) ierr = e
    if (.not. agreed()) return
    call h5_path_exists(file, '/run', exists, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (exists .and. ierr == 0) then
      allocate(character(len=DECK_TEXT_MAX + 1) :: buffer)
      call h5_read_attr_string(file, '/run', 'deck', buffer, e, msg)
      found = e == 0
      if (found) text = trim(buffer)
    end if
    call h5_close_file(file, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (.not. agreed()) return
    found = par_max(merge(0, 1, found)) == 0

  contains

    logical function agreed()
      agreed = par_max(abs(ierr)) == 0
      if (.not. agreed) then
        if (ierr /= 0) then
          call status%add('restart file '''//trim(path)//''': '//trim(msg))
        else
          call status%add('restart file '''//trim(path)//''': failed on another rank')
        end if
      end if
    end function agreed

  end subroutine dump_read_deck

  !> Read a dump into the state of a mesh built from the same deck: positions,
  !> velocities, masses, energies, restart state; ghosts refreshed by halos.
  subroutine dump_read(path, mesh, state, status, contact_work, pair_work, contact_active, &
      contact_resume, contact_offset)
    character(len=*), intent(in) :: path
    type(mesh_t), intent(inout) :: mesh
    type(state_t), intent(inout) :: state
    type(status_t), intent(inout) :: status
    real(rk), intent(inout), optional :: contact_work !< work of the contact forces so far
    real(rk), intent(inout), optional :: pair_work(:) !< the same per contact interface
    !> (nnode local) dump_write's contact_active (zero where the dump has none)
    real(rk), intent(inout), optional :: contact_active(:)
    !> dump_write's contact_resume, emptied when the dump has none
    real(rk), allocatable, intent(inout), optional :: contact_resume(:)
    !> (ndeck, nnode local) dump_write's contact_offset, read when the dump
    !> has it; otherwise no rows
    real(rk), allocatable, intent(inout), optional :: contact_offset(:, :)
    real(rk), allocatable :: nblockk(:, :), klocal(:, :)
    real(rk) :: work
    integer(hid_t) :: file
    integer :: ierr, e, nno, nzo, version, icycle, ncomp, k
    real(rk) :: resume_value
    integer(i8) :: node_first, zone_first, nglobal
    character(len=400) :: msg
    real(rk), allocatable :: nblock3(:, :), nblock1(:, :), zblock(:, :), zlocal(:, :)
    real(rk), allocatable :: zlocal_nodes(:, :)
    real(rk) :: rcycle
    logical :: there

    msg = ''
    ierr = 0
    e = 0
    nno = mesh%nnode_owned
    nzo = mesh%nzone_owned
    node_first = mesh%node_io%first - 1
    zone_first = mesh%zone_io%first - 1
    allocate(nblock3(3, mesh%node_io%nblock), nblock1(1, mesh%node_io%nblock))
    allocate(zblock(1, mesh%zone_io%nblock), zlocal(1, mesh%nzone), zlocal_nodes(1, nno))
    call h5_open_file(path, par_comm_handle(), par_info_null_handle(), file, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (.not. agreed()) return
    call h5_read_attr_int(file, '/', 'format_version', version, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (ierr == 0 .and. version /= FORMAT_VERSION) then
      ierr = 1
      msg = 'format_version is not 1'
    end if
    if (.not. agreed()) return
    call h5_dataset_rows(file, '/zones/density', nglobal, ncomp, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (ierr == 0 .and. nglobal /= mesh%nzone_global) then
      ierr = 1
      msg = 'the dump has a different number of zones than the deck''s mesh'
    end if
    call h5_dataset_rows(file, '/mesh/coordinates', nglobal, ncomp, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (ierr == 0 .and. nglobal /= mesh%nnode_global) then
      ierr = 1
      msg = 'the dump has a different number of nodes than the deck''s mesh'
    end if
    if (.not. agreed()) return
    call h5_read_attr_real(file, '/', 'time', state%time, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_read_attr_int(file, '/', 'cycle', icycle, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_read_attr_real(file, '/restart', 'cycle', rcycle, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    state%cycle = int(rcycle, i8)
    call h5_read_attr_real(file, '/restart', 'dt_previous', state%dt_previous, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (present(pair_work)) then
      do k = 1, size(pair_work)
        call h5_read_attr_real(file, '/run', 'contact_work_'//to_text(k), &
            pair_work(k), e, msg)
        if (e /= 0 .and. ierr == 0) ierr = e
      end do
    end if
    call h5_read_attr_real(file, '/run', 'boundary_work', state%boundary_work, e, msg)
    call h5_read_attr_real(file, '/run', 'contact_work', work, e, msg)
    if (present(contact_work)) contact_work = work
    if (e /= 0 .and. ierr == 0) ierr = e
    call h5_read_attr_real(file, '/run', 'energy_initial', state%energy_initial, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e

    ! The positions at t = 0: the dump's, or for a dump written before they
    ! were kept, the deck's mesh (state%node_position before the read).
    if (.not. allocated(state%node_position_initial)) &
        allocate(state%node_position_initial, source=state%node_position)
    call h5_path_exists(file, '/restart/initial_position', there, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (e == 0 .and. there) then
      call h5_read_real_rows(file, '/restart/initial_position', nblock3, node_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call mesh%node_io%from_block(nblock3, state%node_position_initial(:, 1:nno))
    end if
    call h5_read_real_rows(file, '/mesh/coordinates', nblock3, node_first, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call mesh%node_io%from_block(nblock3, state%node_position(:, 1:nno))
    call h5_read_real_rows(file, '/nodes/velocity', nblock3, node_first, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call mesh%node_io%from_block(nblock3, state%node_velocity(:, 1:nno))
    call h5_read_real_vector(file, '/nodes/mass', nblock1(1, :), node_first, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    call mesh%node_io%from_block(nblock1, zlocal_nodes)
    state%node_mass(1:nno) = zlocal_nodes(1, :)
    call read_zone('/zones/mass', state%zone_mass)
    call read_zone('/zones/specific_internal_energy', state%zone_energy)
    if (allocated(state%zone_stress)) then
      call read_zone('/zones/plastic_strain', state%zone_plastic_strain)
      deallocate(zblock, zlocal)
      allocate(zblock(6, mesh%zone_io%nblock), zlocal(6, mesh%nzone))
      call h5_read_real_rows(file, '/zones/deviatoric_stress', zblock, zone_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call mesh%zone_io%from_block(zblock, zlocal(:, 1:nzo))
      call mesh%zone_halo%exchange(zlocal)
      state%zone_stress = zlocal
      deallocate(zblock, zlocal)
      allocate(zblock(1, mesh%zone_io%nblock), zlocal(1, mesh%nzone))
    end if
    if (allocated(state%zone_hourglass)) then
      deallocate(zblock, zlocal)
      allocate(zblock(12, mesh%zone_io%nblock), zlocal(12, mesh%nzone))
      call h5_read_real_rows(file, '/restart/hourglass_stress', zblock, zone_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call mesh%zone_io%from_block(zblock, zlocal(:, 1:nzo))
      call mesh%zone_halo%exchange(zlocal)
      state%zone_hourglass = reshape(zlocal, [3, 4, mesh%nzone])
    end if
    if (present(contact_resume)) then
      do k = 1, size(contact_resume)
        resume_value = -1.0_rk
        call optional_attribute('contact_resume_'//to_text(k), resume_value)
        if (resume_value < 0.0_rk .and. k == 1) then
          contact_resume = [real(rk) ::]
          exit
        end if
        contact_resume(k) = resume_value
      end do
    end if
    if (present(contact_active)) then
      contact_active = 0.0_rk
      call h5_path_exists(file, '/restart/contact_active', there, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      if (e == 0 .and. there) then
        call h5_read_real_vector(file, '/restart/contact_active', nblock1(1, :), node_first, &
            e, msg)
        if (e /= 0 .and. ierr == 0) ierr = e
        call mesh%node_io%from_block(nblock1, zlocal_nodes)
        contact_active(1:nno) = zlocal_nodes(1, :)
      end if
    end if
    if (present(contact_offset)) then
      call h5_path_exists(file, '/restart/contact_offset', there, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      if (e == 0 .and. there .and. size(contact_offset, 1) > 0) then
        allocate(nblockk(size(contact_offset, 1), mesh%node_io%nblock))
        allocate(klocal(size(contact_offset, 1), nno))
        call h5_read_real_rows(file, '/restart/contact_offset', nblockk, node_first, e, msg)
        if (e /= 0 .and. ierr == 0) ierr = e
        call mesh%node_io%from_block(nblockk, klocal)
        contact_offset = 0.0_rk
        contact_offset(:, 1:nno) = klocal
      else
        deallocate(contact_offset)
        allocate(contact_offset(0, 0))
      end if
    end if
    ! Failure and erosion.
    if (allocated(state%zone_damage)) call read_zone('/zones/damage', state%zone_damage)
    if (allocated(state%zone_alive)) then
      call read_zone('/zones/alive', state%zone_alive)
      ! An eroded zone may have turned inside out: it keeps its last density,
      ! which only the dump has (a live zone's comes from its mass and volume).
      call read_zone('/zones/density', state%zone_density)
      call h5_read_attr_real(file, '/restart', 'dt_reference', state%dt_reference, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call h5_read_real_vector(file, '/restart/eroded_kinetic', nblock1(1, :), node_first, &
          e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call mesh%node_io%from_block(nblock1, zlocal_nodes)
      state%node_eroded_kinetic(1:nno) = zlocal_nodes(1, :)
    end if
    state%stop_kinetic_initial = 0.0_rk
    call optional_attribute('stop_kinetic_initial', state%stop_kinetic_initial)
    ! Energy bookkeeping (absent from dumps written before it: zero then).
    if (allocated(state%zone_plastic_work)) call optional_zone('/restart/plastic_work', &
        state%zone_plastic_work)
    if (allocated(state%zone_hourglass_work)) call optional_zone('/restart/hourglass_work', &
        state%zone_hourglass_work)
    if (.not. agreed()) return
    call h5_close_file(file, e, msg)
    if (e /= 0 .and. ierr == 0) ierr = e
    if (.not. agreed()) return
    call mesh%node_halo%exchange(state%node_position)
    call mesh%node_halo%exchange(state%node_velocity)
    call mesh%node_halo%exchange(state%node_position_initial)

  contains

    !> An attribute of /restart if the dump has it (value unchanged otherwise).
    subroutine optional_attribute(name, value)
      character(len=*), intent(in) :: name
      real(rk), intent(inout) :: value
      real(rk) :: got
      character(len=400) :: why
      why = ''
      call h5_read_attr_real(file, '/restart', name, got, e, why)
      if (e == IO_H5_OK) then
        value = got
      else if (e /= IO_H5_ERR_NOT_FOUND .and. ierr == 0) then
        ierr = e
        msg = why
      end if
      e = 0
    end subroutine optional_attribute

    subroutine optional_zone(name, field)
      character(len=*), intent(in) :: name
      real(rk), intent(inout) :: field(:)
      logical :: there
      call h5_path_exists(file, name, there, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      if (e /= 0) return
      if (there) then
        call read_zone(name, field)
      else
        field = 0.0_rk
      end if
    end subroutine optional_zone

    subroutine read_zone(name, field)
      character(len=*), intent(in) :: name
      real(rk), intent(inout) :: field(:)
      call h5_read_real_vector(file, name, zblock(1, :), zone_first, e, msg)
      if (e /= 0 .and. ierr == 0) ierr = e
      call mesh%zone_io%from_block(zblock(1:1, :), zlocal(1:1, 1:nzo))
      call mesh%zone_halo%exchange(zlocal(1:1, :))
      field = zlocal(1, :)
    end subroutine read_zone

    logical function agreed()
      integer :: worst
      worst = par_max(abs(ierr))
      agreed = worst == 0
      if (.not. agreed) then
        if (ierr /= 0) then
          call status%add('restart file '''//trim(path)//''': '//trim(msg))
        else
          call status%add('restart file '''//trim(path)//''': failed on another rank')
        end if
      end if
    end function agreed

  end subroutine dump_read

end module io_dump
